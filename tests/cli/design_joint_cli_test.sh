#!/usr/bin/env bash
# The loop identify -> design -> log -> identify for the elastic joint
# (docs/models.md#joint-excitation-design): a two-mass joint driven open
# loop by an injected torque (tests/cli/two_mass_injection.awk, written apart
# from driveid: Runge-Kutta with the torque held per sample, noisy motor
# speed, noisy logged torque, 16-bit encoder) under the default multisine
# (0.5-50 Hz, 2 s period, equal lines, Schroeder phases) gives the prior
# through `frf --fit two-mass`; `design joint --target stiffness` (D_s: the
# other parameters nuisance) writes an excitation
# within the torque and speed limits; over three noise seeds the
# frf fits of its logs have stiffness and damping stds at least 2x smaller
# than those of the default multisine at the same rms torque, each within
# 2x of the prediction, and no estimate more than 4 std from the truth.
# Refusals name the option (exit 2) or the file (exit 3).
# Usage: design_joint_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=cli_test_lib.sh
. "$src/tests/cli/cli_test_lib.sh"

# Link side J_m 0.5, J_l 1.5, k 2000, d 2, b_m 6, gear 10 (resonance 11.6 Hz).
joint="-v n=10 -v jm=0.5 -v jl=1.5 -v k=2000 -v d=2 -v bm=6 -v speed_noise=0.02 -v torque_noise=0.002 -v bits=16"
run() { awk $joint -v seed="$1" -f "$src/tests/cli/gauss.awk" -f "$src/tests/cli/two_mass_injection.awk" "$2" > "$3"; }
# multisine RMS SECONDS: the default multisine of `simulate joint`.
multisine() {
  awk -v rms="$1" -v n="$(($2 * 1000))" 'BEGIN { pi = atan2(0, -1); print "t,tau"; L = 100
    for (i = 0; i < n; i++) { p = i % 2000; u = 0
      for (l = 1; l <= L; l++) u += cos(2 * pi * l * p / 2000 - pi * (l - 1) * l / L)
      printf "%.6f,%.9g\n", i / 1000, u * rms * sqrt(2 / L) } }'
}
printf 'joint:\n  gear_ratio: 10\n' > gear.yaml
multisine 0.5 20 > first_excitation.csv
run 1 first_excitation.csv first.csv &&
  "$bin" frf first.csv --params gear.yaml --fit two-mass --reference r -q -o prior.yaml || fail "prior fit"

limits="--duration 40 --max-torque 2 --max-speed 20 --noise 0.02 --torque-noise 0.002"
"$bin" design joint --params prior.yaml $limits --target stiffness -o next.csv --json > design.json \
  2> design.err && ok || fail "design: $(cat design.err)"
# The torque limit on the written excitation; its peak as the design says.
peak=$(grep -o '"peaks":{[^}]*}' design.json | head -1 | grep -o '"torque":[0-9.e+-]*' | cut -d: -f2)
awk -F, -v said="$peak" '/^#/ || /^t,/ { next } { v = $2 < 0 ? -$2 : $2; if (v > m) m = v; n++ }
  END { printf "%d %g (design: %g)\n", n, m, said; exit !(n == 40000 && m <= 2 && m > 0.99 * said && m < 1.01 * said) }' \
  next.csv > peaks.txt && ok || fail "torque limit: rows, |tau| = $(cat peaks.txt)"
rms=$(grep -o '"rms_torque":[0-9.e+-]*' design.json | head -1 | cut -d: -f2)
multisine "$rms" 40 > flat.csv

predicted() { grep -o "\"$2\":{[^}]*}" design.json | sed -n "$1p" | grep -o "\"$3\":[0-9.e+-]*" | cut -d: -f2; }
field() { awk -v name="$2" -v col="$3" '/^  estimates:/ { f = 1; next } f && $1 == name ":" { gsub(/[{},]/, " "); print $col; exit }' "$1"; }
: > stds.txt
for seed in 2 3 4; do
  for excitation in next flat; do
    run "$seed" "$excitation.csv" "$excitation-$seed.csv"
    if ! "$bin" frf "$excitation-$seed.csv" --params gear.yaml --fit two-mass --reference r -q -o "$excitation-$seed.yaml" \
      2> err.txt; then
      fail "frf of $excitation seed $seed: $(cat err.txt)"
      continue
    fi
    for p in motor_inertia:0.5 link_inertia:1.5 stiffness:2000 damping:2 motor_viscous:6; do
      name=${p%%:*} truth=${p#*:}
      value=$(field "$excitation-$seed.yaml" "$name" 3) std=$(field "$excitation-$seed.yaml" "$name" 5)
      echo "$excitation $name $std" >> stds.txt
      awk -v v="$value" -v s="$std" -v t="$truth" 'BEGIN { z = (v - t) / s; exit !(s > 0 && z < 4 && z > -4) }' ||
        fail "$excitation seed $seed: $name = $value +- $std, truth $truth"
    done
  done
done
# The designed log's peak motor speed (measured, noise included) within the limit.
awk -F, '/^#/ || /^t,/ { next } { v = $4 < 0 ? -$4 : $4; if (v > m) m = v } END { print m; exit !(m <= 20) }' \
  next-2.csv > speed.txt && ok || fail "speed limit: |qd_motor| = $(cat speed.txt)"
mean_std() { awk -v e="$1" -v p="$2" '$1 == e && $2 == p { s += $3; n++ } END { if (n) print s / n }' stds.txt; }
for p in stiffness damping; do
  designed=$(mean_std next "$p") flat=$(mean_std flat "$p")
  awk -v d="$designed" -v f="$flat" 'BEGIN { exit !(d > 0 && f / d >= 2) }' && ok ||
    fail "$p std: designed $designed, default multisine $flat (expected at least 2x smaller)"
done
for p in motor_inertia link_inertia stiffness damping motor_viscous; do
  for pair in "1 next" "2 flat"; do
    achieved=$(mean_std "${pair#* }" "$p") expected=$(predicted "${pair% *}" predicted_std "$p")
    awk -v a="$achieved" -v e="$expected" 'BEGIN { exit !(a > 0 && e > 0 && a < 2 * e && e < 2 * a) }' && ok ||
      fail "$p (${pair#* }): achieved std $achieved, predicted $expected (not within 2x)"
  done
done

# simulate joint --reference injects the design.
"$bin" simulate joint --params prior.yaml --reference next.csv --noise 0.02 -o tried.csv > /dev/null 2> err.txt &&
  [ "$(grep -vc '^#' tried.csv)" -eq 40001 ] && ok || fail "simulate --reference: $(cat err.txt)"

# Refusals.
expect 2 "--target foo: not a free parameter" -- design joint --params prior.yaml $limits --target foo
expect 2 "--free motor_coulomb" -- design joint --params prior.yaml $limits --free motor_coulomb,stiffness
expect 2 "--duration 8 s: at least 5 periods" -- design joint --params prior.yaml --duration 8 --max-torque 2 \
  --max-speed 20 --noise 0.02
printf 't,tau\n0,0\n0.001,1\n0.003,2\n' > uneven.csv
for k in $(seq 4 20); do printf '0.%03d,0\n' $((k + 2)) >> uneven.csv; done
"$bin" simulate joint --params prior.yaml --reference uneven.csv > /dev/null 2> err.txt
code=$?
[ "$code" -eq 3 ] && grep -q "uneven.csv" err.txt && ok || fail "uneven reference: exit $code, $(cat err.txt)"
printf 't,tau\n0,0\n0.001,x\n' > bad.csv
"$bin" simulate joint --params prior.yaml --reference bad.csv > /dev/null 2> err.txt
code=$?
[ "$code" -eq 3 ] && grep -q "bad.csv:3" err.txt && ok || fail "bad reference: exit $code, $(cat err.txt)"
finish
