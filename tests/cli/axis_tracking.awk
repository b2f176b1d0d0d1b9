# An axis under a stiff position loop, written apart from driveid's code (a
# test generator for `design axis`): the loop reads a quantised encoder,
# differentiates it, and commands u = kp (r - q_m) + kd (r' - v_m) + J r''
# each logger step; the axis sees u held over the step (zero-order hold,
# as a drive applies its last command) with viscous, sticking Coulomb and
# offset torques; the logged torque is u plus Gaussian noise (a measured
# current). With loop=continuous the loop is analog instead: u is
# recomputed at every integration substep from the true state and the
# reference between samples (the quintic through each end's q, qd and qdd,
# so that r, r' and r'' agree: interpolating the three linearly leaves a
# ripple at the logging rate, kp x(1-x) h^2 r''/2, that a sampled torque
# aliases to -(w h)^2/12 of J r'', -0.13 % at 20 Hz and 1 kHz), and the
# logged torque is u at the sample's instant (a current sampled with the
# position; the log's encoder is still quantised).
# Input: a reference CSV with header t,q,qd,qdd. Output: t,q,tau.
# With logged=previous the log is as ros2_control writes it: the effort in
# row k is the command that was held over the step before it (u_(k-1)),
# i.e. the torque acts half a sample before its stamp.
# Variables: J, b, tc, t0 (the axis), bw (loop bandwidth [Hz]), bits (encoder
# counts per turn as 2^bits), noise (std of the logged torque), seed, steps
# (integration substeps per logger step), loop (continuous or empty),
# logged (previous or empty).
# Run as awk -f gauss.awk -f axis_tracking.awk (gauss(): a normal deviate).
function sgn(x) { return x > 0 ? 1 : (x < 0 ? -1 : 0) }
# The quintic Hermite reference at x in [0, 1] of step k (length dt):
# sets rx, rdx, rddx.
function quintic(k, x, dt,    x2, x3, x4, x5, v0, a0, v1, a1) {
  x2 = x * x; x3 = x2 * x; x4 = x3 * x; x5 = x4 * x
  v0 = rd[k] * dt; a0 = rdd[k] * dt * dt; v1 = rd[k + 1] * dt; a1 = rdd[k + 1] * dt * dt
  rx = r[k] * (1 - 10 * x3 + 15 * x4 - 6 * x5) + v0 * (x - 6 * x3 + 8 * x4 - 3 * x5) + \
       a0 * (x2 - 3 * x3 + 3 * x4 - x5) / 2 + r[k + 1] * (10 * x3 - 15 * x4 + 6 * x5) + \
       v1 * (-4 * x3 + 7 * x4 - 3 * x5) + a1 * (x3 - 2 * x4 + x5) / 2
  rdx = (r[k] * (-30 * x2 + 60 * x3 - 30 * x4) + v0 * (1 - 18 * x2 + 32 * x3 - 15 * x4) + \
         a0 * (2 * x - 9 * x2 + 12 * x3 - 5 * x4) / 2 + r[k + 1] * (30 * x2 - 60 * x3 + 30 * x4) + \
         v1 * (-12 * x2 + 28 * x3 - 15 * x4) + a1 * (3 * x2 - 8 * x3 + 5 * x4) / 2) / dt
  rddx = (r[k] * (-60 * x + 180 * x2 - 120 * x3) + v0 * (-36 * x + 96 * x2 - 60 * x3) + \
          a0 * (2 - 18 * x + 36 * x2 - 20 * x3) / 2 + r[k + 1] * (60 * x - 180 * x2 + 120 * x3) + \
          v1 * (-24 * x + 84 * x2 - 60 * x3) + a1 * (6 * x - 24 * x2 + 20 * x3) / 2) / (dt * dt)
}
BEGIN {
  FS = ","; srand(seed + 0)
  if (steps == "") steps = 20
  w = 6.283185307179586 * bw; kp = J * w * w; kd = 2 * 0.8 * J * w
  quantum = 6.283185307179586 / 2 ^ bits
  q = 0; v = 0; qm_prev = 0; n = 0
  print "t,q,tau"
}
/^#/ { next }
!header { header = 1; next }
{
  t[n] = $1; r[n] = $2; rd[n] = $3; rdd[n] = $4; n++
}
END {
  for (k = 0; k < n; k++) {
    dt = k + 1 < n ? t[k + 1] - t[k] : t[k] - t[k - 1]
    qm = quantum * int(q / quantum + (q >= 0 ? 0.5 : -0.5))
    vm = k > 0 ? (qm - qm_prev) / dt : 0
    qm_prev = qm
    u = kp * (r[k] - qm) + kd * (rd[k] - vm) + J * rdd[k]
    if (loop == "continuous") u = kp * (r[k] - q) + kd * (rd[k] - v) + J * rdd[k]
    logged_u = logged == "previous" ? (k > 0 ? u_prev : 0) : u
    printf "%.6f,%.10g,%.7g\n", t[k], qm, logged_u + noise * gauss()
    u_prev = u
    h = dt / steps
    for (s = 0; s < steps; s++) {
      if (loop == "continuous" && s > 0 && k + 1 < n) {
        quintic(k, s / steps, dt)
        u = kp * (rx - q) + kd * (rdx - v) + J * rddx
      }
      f = u - b * v - t0
      if (v == 0 && (f > -tc && f < tc)) a = 0
      else a = (f - tc * sgn(v != 0 ? v : f)) / J
      vn = v + a * h
      q += 0.5 * (v + vn) * h
      v = (v != 0 && sgn(vn) != sgn(v)) ? 0 : vn
    }
  }
}
