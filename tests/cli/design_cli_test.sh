#!/usr/bin/env bash
# The loop identify -> design -> log -> identify (docs/guide.md#designing-the-next-experiment)
# on an axis under a stiff position loop (tests/cli/axis_tracking.awk,
# written apart from driveid: quantised encoder, noisy logged torque, the
# command held over each logger step): a first log tracking four equal sines
# (0.2-2 Hz) gives the prior; `design axis` writes a reference that keeps
# every limit; the fit of its tracking log, with defaults, warns of nothing,
# holds the truth in every interval, has each std within 2x of the
# prediction and a geometric-mean std at least 1.5x smaller than four
# sines' at the same limits; the same loop run continuously (a measured
# current) is read as sampled, with every estimate within 3 std.
# Refusals name the option (exit 2) or the file and line (exit 3).
# Usage: design_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=cli_test_lib.sh
. "$src/tests/cli/cli_test_lib.sh"

truth="-v J=0.05 -v b=0.2 -v tc=1 -v t0=0.3 -v bw=20 -v bits=16 -v noise=0.05"
track() { awk $truth -v seed="$1" -f "$src/tests/cli/gauss.awk" -f "$src/tests/cli/axis_tracking.awk" "$2" > "$3"; }
# Four equal sines 0.2-2 Hz within |qd| <= 2 (the hand-made test).
awk 'BEGIN { pi = 3.141592653589793; split("0.2 0.430887 0.928318 2.0", f, " "); print "t,q,qd,qdd"
  for (k = 0; k <= 20000; k++) { t = k / 1000; q = 0; v = 0; a = 0
    for (i = 1; i <= 4; i++) { w = 2 * pi * f[i]; q += 0.0875 * sin(w * t); v += 0.0875 * w * cos(w * t); a -= 0.0875 * w * w * sin(w * t) }
    printf "%.6f,%.10g,%.10g,%.10g\n", t, q, v, a } }' > four.csv
track 1 four.csv first.csv && "$bin" axis first.csv -q -o prior.yaml || fail "prior fit"

limits="--duration 20 --max-position 1 --max-speed 2 --max-torque 3"
"$bin" design axis --params prior.yaml $limits -o next.csv --json > design.json 2> design.err && ok ||
  fail "design: $(cat design.err)"
# Every limit on the written reference, the torque from the truth.
awk -F, '/^#/ || /^t,/ { next } { q = $2 < 0 ? -$2 : $2; v = $3 < 0 ? -$3 : $3
  tau = 0.05 * $4 + 0.2 * $3 + ($3 > 0 ? 1 : ($3 < 0 ? -1 : 0)) + 0.3; if (tau < 0) tau = -tau
  if (q > mq) mq = q; if (v > mv) mv = v; if (tau > mt) mt = tau; n++ }
  END { printf "%d %g %g %g\n", n, mq, mv, mt; exit !(n == 20001 && mq <= 1 && mv <= 2 && mt <= 3 && mt > 2.5) }' next.csv > peaks.txt &&
  ok || fail "limits: rows, |q|, |qd|, |tau| = $(cat peaks.txt)"

track 2 next.csv designed.csv && "$bin" axis designed.csv -o designed.yaml > designed.txt 2> designed.err ||
  fail "fit of the designed log"
# Right with defaults (docs/models.md#axis-exclusion, #torque-timing): no
# warning, the held command read as held, the truth inside every 95 %
# interval; read as sampled instead, viscous and Coulomb are far off.
[ ! -s designed.err ] && ok || fail "warnings on the designed log: $(cat designed.err)"
awk '/^torque timing delay/ { found = 1; d = $4 + 0 } END { exit !(found && d > 0.3 && d < 0.7) }' designed.txt && ok ||
  fail "torque timing not held (+0.5): $(grep timing designed.txt)"
inside() { awk -v name="$2" -v truth="$3" '/^  estimates:/ { f = 1; next }
  f && $1 == name ":" { gsub(/[][{},]/, " "); exit !($7 <= truth && truth <= $8) }' "$1"; }
for pair in inertia=0.05 viscous=0.2 coulomb=1 offset=0.3; do
  inside designed.yaml "${pair%=*}" "${pair#*=}" && ok || fail "${pair%=*}: truth ${pair#*=} outside $(grep "  ${pair%=*}:" designed.yaml)"
done
z_of() { awk -v name="$2" -v truth="$3" '/^  estimates:/ { f = 1; next }
  f && $1 == name ":" { gsub(/[{},]/, " "); printf "%.2f\n", ($3 - truth) / $5; exit }' "$1"; }
"$bin" axis designed.csv --torque-timing sampled -q -o sampled.yaml 2> /dev/null || fail "sampled fit"
z_sampled=$(z_of sampled.yaml coulomb 1)
awk -v s="$z_sampled" 'BEGIN { exit !(s > 5 || s < -5) }' && ok || fail "coulomb z read as sampled: $z_sampled (expected beyond 5)"
# validate reads a held log as the fit did (the file records the fit's
# reading, +0.5: the default) and as --torque-timing held says: a smaller
# rmse on another seed's log than read as sampled.
track 6 next.csv other.csv || fail "other seed"
rmse_of() { awk '/:tau / { print $3; exit }' "$1"; }
"$bin" validate designed.yaml other.csv --torque-timing held > v_held.txt 2>&1 &&
  "$bin" validate designed.yaml other.csv --torque-timing sampled > v_sampled.txt 2>&1 &&
  "$bin" validate designed.yaml other.csv > v_file.txt 2>&1 &&
  grep -q "torque held" v_held.txt && grep -q "torque delay +0.500 samples (the fit's, from the file)" v_file.txt &&
  [ "$(rmse_of v_file.txt)" = "$(rmse_of v_held.txt)" ] &&
  awk -v h="$(rmse_of v_held.txt)" -v s="$(rmse_of v_sampled.txt)" 'BEGIN { exit !(h > 0 && h < 0.95 * s) }' && ok ||
  fail "validate --torque-timing held: $(cat v_held.txt v_sampled.txt v_file.txt)"
# The same loop run continuously (the torque a measured current): read as sampled.
awk $truth -v seed=5 -v loop=continuous -v steps=100 -f "$src/tests/cli/gauss.awk" -f "$src/tests/cli/axis_tracking.awk" \
  next.csv > current.csv && "$bin" axis current.csv -o current.yaml > current.txt 2> current.err ||
  fail "fit of the current log"
awk '/^torque timing delay/ { found = 1; d = $4 + 0 } END { exit !(found && d > -0.2 && d < 0.2) }' current.txt && ok ||
  fail "torque timing not sampled (0): $(grep timing current.txt)"
# Within 3 std: where the residual rule picks half the band (half the
# seeds), Coulomb keeps a bias of about 2 std, the friction step spread
# further than the fit leaves out (docs/models.md, known limits of the
# excitation design).
for pair in inertia=0.05 viscous=0.2 coulomb=1 offset=0.3; do
  z=$(z_of current.yaml "${pair%=*}" "${pair#*=}")
  awk -v z="$z" 'BEGIN { exit !(z > -3 && z < 3) }' && ok || fail "current log: ${pair%=*}: z $z (expected within 3)"
done
track 3 four.csv again.csv && "$bin" axis again.csv -q -o again.yaml || fail "fit of four sines"
std_of() { awk -v name="$2" '/^  estimates:/ { f = 1; next } f && $1 == name ":" { gsub(/[{},]/, " "); print $5; exit }' "$1"; }
ratio_product=1
for p in inertia viscous coulomb offset; do
  predicted=$(grep -o "\"predicted_std\":{[^}]*}" design.json | head -1 | grep -o "\"$p\":[0-9.e+-]*" | cut -d: -f2)
  achieved=$(std_of designed.yaml "$p")
  awk -v a="$achieved" -v p="$predicted" 'BEGIN { exit !(a > 0 && p > 0 && a < 2 * p && p < 2 * a) }' && ok ||
    fail "$p: achieved std $achieved, predicted $predicted (not within 2x)"
  ratio_product=$(awk -v r="$ratio_product" -v d="$achieved" -v f="$(std_of again.yaml "$p")" 'BEGIN { printf "%.10g", r * f / d }')
done
# The geometric mean of the four stds at least 1.5x smaller than four sines'.
awk -v r="$ratio_product" 'BEGIN { exit !(r ^ 0.25 >= 1.5) }' && ok ||
  fail "geometric-mean std ratio $(awk -v r="$ratio_product" 'BEGIN { print r ^ 0.25 }') (expected >= 1.5)"

# A ros2_control-style log (docs/models.md#torque-timing): a 250 Hz PD loop,
# the effort logged as the command held over the step before it, so the
# torque acts half a sample before its stamp; viscous 1.5 and Coulomb 2
# (both readings the fit used to choose between are off by many std here).
awk 'BEGIN { print "t,q,qd,qdd"; for (k = 0; k <= 7500; ++k) { t = k / 250; q = 0; v = 0; a = 0;
  split("0.13 0.31 0.71", f, " "); split("0.8 0.35 0.12", m, " ");
  for (i = 1; i <= 3; ++i) { w = 6.283185307179586 * f[i]; q += m[i] * sin(w * t); v += m[i] * w * cos(w * t); a -= m[i] * w * w * sin(w * t) }
  printf "%.6f,%.10g,%.10g,%.10g\n", t, q, v, a } }' > ros_reference.csv
awk -v J=0.05 -v b=1.5 -v tc=2 -v t0=0 -v bw=15 -v bits=18 -v noise=0.02 -v seed=4 -v logged=previous \
  -f "$src/tests/cli/gauss.awk" -f "$src/tests/cli/axis_tracking.awk" ros_reference.csv > ros.csv &&
  "$bin" axis ros.csv -o ros.yaml > ros.txt 2> ros.err || fail "fit of the ros2_control-style log: $(cat ros.err)"
awk '/^torque timing delay/ { found = 1; d = $4 + 0 } END { exit !(found && d > -0.7 && d < -0.3) }' ros.txt && ok ||
  fail "ros2_control timing: $(grep 'torque timing' ros.txt)"
for pair in inertia=0.05 viscous=1.5 coulomb=2; do
  inside ros.yaml "${pair%=*}" "${pair#*=}" && ok || fail "ros2_control log: ${pair%=*}: truth ${pair#*=} outside $(grep "  ${pair%=*}:" ros.yaml)"
done
grep -q "^  torque_delay: -0\.[3-7]" ros.yaml && ok || fail "the timing is not recorded: $(grep torque_delay ros.yaml)"
# validate reuses the recorded timing by default, as given by hand.
"$bin" validate ros.yaml ros.csv > v_file.txt 2>&1 &&
  "$bin" validate ros.yaml ros.csv --torque-timing "$(awk '/^  torque_delay:/ { print $2 }' ros.yaml)" > v_given.txt 2>&1 &&
  grep -q "the fit's, from the file" v_file.txt && [ "$(rmse_of v_file.txt)" = "$(rmse_of v_given.txt)" ] && ok ||
  fail "validate does not reuse the fit's timing: $(cat v_file.txt v_given.txt)"

# simulate --reference: the prior's axis following the design exactly.
"$bin" simulate axis --params prior.yaml --reference next.csv --noise 0.05 -o tried.csv > /dev/null &&
  [ "$(grep -vc '^#' tried.csv)" -eq 20002 ] && ok || fail "simulate --reference"

# Refusals.
"$bin" design axis --params prior.yaml $limits --free inertia,stribeck > /dev/null 2> err.txt
code=$?
[ "$code" -eq 2 ] && grep -q -- "--free stribeck" err.txt && ok || fail "--free stribeck: exit $code, $(cat err.txt)"
printf 'axis:\n  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1\n  offset: 0.3\n' > nofit.yaml
"$bin" design axis --params nofit.yaml $limits > /dev/null 2> err.txt
code=$?
[ "$code" -eq 2 ] && grep -q -- "--noise" err.txt && ok || fail "prior without a fit: exit $code, $(cat err.txt)"
"$bin" design axis --params nofit.yaml --noise 0.05 --duration 20 --max-position 1 --max-speed 2 --max-torque 1.2 \
  > /dev/null 2> err.txt
code=$?
[ "$code" -eq 2 ] && grep -q -- "--max-torque" err.txt && ok || fail "torque below the friction: exit $code, $(cat err.txt)"
# A band beyond the log's Nyquist frequency, or past the period's 2000th
# harmonic, is refused by name (issue 55: "internal error: sizes").
for band in 0,1e9 1e9,2e9 0.1,499; do
  "$bin" design axis --params prior.yaml $limits --band $band --period 10 > /dev/null 2> err.txt
  code=$?
  [ "$code" -eq 2 ] && grep -qE -- "--band .*Nyquist|--period 10 s: the band's top" err.txt && ok ||
    fail "--band $band: exit $code, $(cat err.txt)"
done
printf 't,q\n0,0\n0.001,x\n' > bad.csv
"$bin" simulate axis --params nofit.yaml --reference bad.csv > /dev/null 2> err.txt
code=$?
[ "$code" -eq 3 ] && grep -q "bad.csv:3" err.txt && ok || fail "bad reference: exit $code, $(cat err.txt)"
finish
