# An axis under a stiff position loop, written apart from driveid's code (a
# test generator for `design axis`): the loop reads a quantised encoder,
# differentiates it, and commands u = kp (r - q_m) + kd (r' - v_m) + J r''
# each logger step; the axis sees u held over the step (zero-order hold,
# as a drive applies its last command) with viscous, sticking Coulomb and
# offset torques; the logged torque is u plus Gaussian noise (a measured
# current). With loop=continuous the loop is analog instead: u is
# recomputed at every integration substep from the true state and the
# linearly interpolated reference, and the logged torque is u at the
# sample's instant (a current sampled with the position; the log's encoder
# is still quantised).
# Input: a reference CSV with header t,q,qd,qdd. Output: t,q,tau.
# Variables: J, b, tc, t0 (the axis), bw (loop bandwidth [Hz]), bits (encoder
# counts per turn as 2^bits), noise (std of the logged torque), seed, steps
# (integration substeps per logger step), loop (continuous or empty).
# Run as awk -f gauss.awk -f axis_tracking.awk (gauss(): a normal deviate).
function sgn(x) { return x > 0 ? 1 : (x < 0 ? -1 : 0) }
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
    printf "%.6f,%.10g,%.7g\n", t[k], qm, u + noise * gauss()
    h = dt / steps
    for (s = 0; s < steps; s++) {
      if (loop == "continuous" && s > 0 && k + 1 < n) {
        x = s / steps
        u = kp * (r[k] + x * (r[k + 1] - r[k]) - q) + kd * (rd[k] + x * (rd[k + 1] - rd[k]) - v) + \
            J * (rdd[k] + x * (rdd[k + 1] - rdd[k]))
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
