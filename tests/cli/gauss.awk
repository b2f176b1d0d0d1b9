# A standard normal deviate by Box-Muller from awk's rand() (seeded by the
# caller's srand), shared by the test generators (awk -f gauss.awk -f GEN).
function gauss() {
  if (spare_ok) { spare_ok = 0; return spare }
  do { u1 = rand() } while (u1 <= 1e-300)
  u2 = rand()
  rad = sqrt(-2 * log(u1)); spare = rad * sin(6.283185307179586 * u2); spare_ok = 1
  return rad * cos(6.283185307179586 * u2)
}
