# A two-mass joint driven open loop by an injected torque read from a CSV
# (t,tau: the excitation `design joint` writes), written apart from
# driveid's code (a test generator for `design joint`): link-side motor and
# link inertias, spring and damper, motor viscous friction, gear ratio n;
# the torque is held over each logger step (classic Runge-Kutta, `steps`
# sub-steps); logged: the torque with Gaussian noise (a measured current),
# the motor angle on a 2^bits-count encoder, the motor speed with Gaussian
# noise, the link angle, and the injected excitation r (as a drive logs its
# test signal). Input rows are replayed `repeat` times.
# Variables: n jm jl k d bm (the joint), speed_noise, torque_noise, bits,
# seed, steps, repeat. Output: t,tau,q_motor,qd_motor,q_link,r.
# Run as awk -f gauss.awk -f two_mass_injection.awk (gauss(): a normal deviate).
# d/dt (xm, vm, xl, vl) at the state (a, b, c, e) under motor torque tm.
function slope(a, b, c, e, tm) {
  f = k * (a - c) + d * (b - e)
  da = b; db = (tm - f - bm * b) / jm; dc = e; de = f / jl
}
# One classic Runge-Kutta step of length h, the torque held.
function rk4(tm) {
  slope(xm, vm, xl, vl, tm); a1 = da; b1 = db; c1 = dc; e1 = de
  slope(xm + h / 2 * a1, vm + h / 2 * b1, xl + h / 2 * c1, vl + h / 2 * e1, tm); a2 = da; b2 = db; c2 = dc; e2 = de
  slope(xm + h / 2 * a2, vm + h / 2 * b2, xl + h / 2 * c2, vl + h / 2 * e2, tm); a3 = da; b3 = db; c3 = dc; e3 = de
  slope(xm + h * a3, vm + h * b3, xl + h * c3, vl + h * e3, tm)
  xm += h / 6 * (a1 + 2 * a2 + 2 * a3 + da); vm += h / 6 * (b1 + 2 * b2 + 2 * b3 + db)
  xl += h / 6 * (c1 + 2 * c2 + 2 * c3 + dc); vl += h / 6 * (e1 + 2 * e2 + 2 * e3 + de)
}
BEGIN {
  FS = ","; srand(seed + 0)
  if (steps == "") steps = 4
  if (repeat == "") repeat = 1
  quantum = 6.283185307179586 / 2 ^ bits
  xm = 0; vm = 0; xl = 0; vl = 0; rows = 0
  print "t,tau,q_motor,qd_motor,q_link,r"
}
/^#/ { next }
!header { header = 1; next }
{ t[rows] = $1; u[rows] = $2; rows++ }
END {
  dt = t[1] - t[0]
  h = dt / steps
  for (r = 0; r < repeat; r++) {
    for (i = 0; i < rows; i++) {
      qm = quantum * int(n * xm / quantum + (xm >= 0 ? 0.5 : -0.5))
      printf "%.6f,%.9g,%.10g,%.9g,%.10g,%.9g\n", (r * rows + i) * dt, u[i] + torque_noise * gauss(), qm,
        n * vm + speed_noise * gauss(), xl, u[i]
      for (s = 0; s < steps; s++) rk4(n * u[i])
    }
  }
}
