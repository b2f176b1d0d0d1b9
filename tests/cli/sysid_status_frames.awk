# SysId-style log as WPILib's logger writes it: rows every 5 ms (+- 0.35 ms
# jitter), the commanded voltage at the row quantised to 12/1023 V, position
# (1/2048 rad) and velocity from the controller's 20 ms status frames (random
# phase per test). kind = flywheel | arm. Exact sub-steps of 0.1 ms
# (flywheel) / semi-implicit Euler (arm); Coulomb friction sticks at rest.
# With -v vframe=0.01 the logged voltage is the controller's applied voltage
# from its own 10 ms frames, with 10 mV of battery noise on each.
function gauss() { return sqrt(-2 * log(1 - rand())) * cos(6.283185307179586 * rand()) }
function sgn(x) { return x > 0 ? 1 : (x < 0 ? -1 : 0) }
function volts(name, t) {
  if (name ~ /slow/) return (name ~ /forward/ ? 1 : -1) * 0.25 * t
  return (name ~ /forward/ ? 1 : -1) * (kind == "arm" ? 4 : 7)
}
function test(name, T, q0,    t, q, v, h, u, g, drive, s, vinf, e, next_row, next_frame, next_volts, fq, fv, fu, lu, out, first, a) {
  h = 0.0001; q = q0; v = 0; t = 0; next_row = 0; next_frame = rand() * 0.02; fq = q; fv = v; out = ""; first = 1
  next_volts = vframe > 0 ? rand() * vframe : 1e9; fu = volts(name, 0)
  while (t < T) {
    while (next_frame <= t + 1e-12) { fq = q; fv = v; next_frame += 0.02 }
    while (next_volts <= t + 1e-12) { fu = volts(name, t) + 0.01 * gauss(); next_volts += vframe }
    if (next_row <= t + 1e-12) {
      lu = vframe > 0 ? fu : volts(name, t)
      out = out (first ? "" : ", ") sprintf("[%.6f, %.10g, %.10g, %.10g]", t, int(lu * 1023 / 12 + (lu >= 0 ? 0.5 : -0.5)) * 12 / 1023, int(fq * 2048 + (fq >= 0 ? 0.5 : -0.5)) / 2048, fv)
      first = 0; next_row += 0.005 + 0.00035 * gauss()
    }
    u = volts(name, t); g = kind == "arm" ? Kg * cos(q) : 0; drive = u - g
    if (v == 0 && (drive < 0 ? -drive : drive) <= Ks) { t += h; continue }
    s = v != 0 ? sgn(v) : sgn(drive)
    if (kind == "arm") {
      a = (drive - Ks * s - Kv * v) / Ka; v += a * h; q += v * h
    } else {
      vinf = (drive - Ks * s) / Kv; e = exp(-h * Kv / Ka)
      q += vinf * h + (v - vinf) * (1 - e) * Ka / Kv; v = vinf + (v - vinf) * e
    }
    if (sgn(v) != s && (drive < 0 ? -drive : drive) <= Ks) v = 0
    t += h
  }
  return "\"" name "\": [" out "]"
}
BEGIN {
  srand(seed)
  if (kind == "arm") { Ks = 0.3; Kv = 1.5; Ka = 0.08; Kg = 0.6; slow = 8; fast = 1 } else { Ks = 0.25; Kv = 0.12; Ka = 0.005; Kg = 0; slow = 14; fast = 2 }
  lo = kind == "arm" ? -1.3707963267948966 : 0; hi = kind == "arm" ? 1.8707963267948966 : 0
  printf "{\"test\": \"%s\", \"units\": \"Radians\", \"unitsPerRotation\": 1.0, %s, %s, %s, %s}\n", kind == "arm" ? "Arm" : "Simple",
    test("slow-forward", slow, lo), test("slow-backward", slow, hi), test("fast-forward", fast, lo), test("fast-backward", fast, hi)
}
