#!/usr/bin/env bash
# A drivetrain test bench as benches log it (docs/models.md#elastic-joint,
# shaft-torque channel): two encoder speeds and a shaft torque transducer,
# no motor torque. Generated here in awk (semi-implicit Euler, 10 sub-steps;
# independent of the library): motor J_m 0.01 and load J_l 0.05 kg m^2 on a
# shaft of k 94 N m/rad, d 0.02 N m s/rad, a multisine motor torque, speeds
# with white noise, the transducer with a 0.3 N m bias and noise. Fitted
# with flags only (angles integrated from the speeds); a log that does not
# determine the stiffness is refused by name; logs that disagree are named.
# Usage: bench_cli_test.sh DRIVETRAIN_FIT SOURCE_DIR
set -u
bin="$1"
src="$2"
program=drivetrain-fit
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

# bench K AMPLITUDE SEED [JS]: columns time, motor speed, load speed, shaft
# torque (no header); JS: the transducer sits on the motor side with an
# inertia JS between it and the shaft (it reads shaft + JS x motor acceleration).
bench() {
  awk -v k="$1" -v amp="$2" -v seed="$3" -v js="${4:-0}" 'BEGIN {
    jm = 0.01; jl = 0.05; d = 0.02; bm = 0.005; bl = 0.02; rate = 2000; ns = 10; h = 1 / (rate * ns);
    pi = atan2(0, -1); srand(seed);
    for (i = 0; i < 20000; ++i) {
      t = i / rate; u = 0;
      for (l = 1; l <= 40; ++l) u += amp * sin(2 * pi * l * t + pi * l * l / 40);
      shaft = k * (xm - xl) + d * (vm - vl); am = (u - shaft - bm * vm) / jm;
      printf "%.5f %.7g %.7g %.7g\n", t, vm + 0.002 * (rand() - 0.5), vl + 0.002 * (rand() - 0.5),
             shaft + js * am + 0.3 + 0.01 * (rand() - 0.5);
      for (s = 0; s < ns; ++s) {
        f = k * (xm - xl) + d * (vm - vl);
        vm += h * (u - f - bm * vm) / jm; vl += h * (f - bl * vl) / jl;
        xm += h * vm; xl += h * vl;
      }
    }
  }'
}
bench 94 0.05 1 > bench1.txt
bench 94 0.05 2 > bench2.txt
bench 60 0.05 3 > bench_soft.txt
# Constant speed, no torque variation: the deflection does not move.
awk 'BEGIN { for (i = 0; i < 20000; ++i) printf "%.5f %.7g %.7g %.7g\n", i / 2000, 1 + 0.002 * ((i * 7919) % 13) / 13,
             1 + 0.002 * ((i * 104729) % 17) / 17, 0.3 + 0.01 * ((i * 31) % 11) / 11 }' > steady.txt
printf 'joint:\n  gear_ratio: 1\n' > bench.yaml
flags=(--no-header --delimiter space --col 't=#1' --col 'q_motor=integral(#2)' --col 'q_link=integral(#3)'
       --col 'tau_link=#4' --params bench.yaml)

"$bin" joint bench1.txt "${flags[@]}" -o fit.yaml > summary.txt 2>&1 || fail "bench fit: $(cat summary.txt)"
awk '/^  stiffness:/ { exit !($2 > 91 && $2 < 97) }' fit.yaml && ok || fail "stiffness: $(grep stiffness fit.yaml)"
awk '/^  link_torque_offset:/ { exit !($2 > 0.2 && $2 < 0.4) }' fit.yaml && ok \
  || fail "offset: $(grep link_torque_offset fit.yaml)"
grep -q "q_motor = integral(#2)" fit.yaml && ok || fail "provenance lacks the expression: $(grep -A3 'data:' fit.yaml)"
! grep -q "residual follows the accelerations" summary.txt && ok || fail "a sensor between the encoders taken for a misplaced one"
# The transducer on the motor side behind half the motor's inertia: the
# stiffness halves (47 for 94), and the warning says why with that inertia.
bench 94 0.05 1 0.005 > misplaced.txt
"$bin" joint misplaced.txt "${flags[@]}" -o misplaced.yaml > misplaced_summary.txt 2>&1 &&
  grep -Eq "^warning: model: the shaft torque's residual follows the accelerations .* it reads 0.00(49|50|51)[0-9]* kg m\^2 x the motor's" misplaced_summary.txt &&
  ok || fail "misplaced shaft-torque sensor not named: $(grep warning misplaced_summary.txt)"
# Two repeats agree; a softer shaft among them is named.
"$bin" joint bench1.txt bench2.txt "${flags[@]}" -o fit2.yaml > two.txt 2>&1 && ! grep -q "disagree" two.txt && ok \
  || fail "two repeats: $(cat two.txt)"
"$bin" joint bench1.txt bench2.txt bench_soft.txt "${flags[@]}" -o fit3.yaml > three.txt 2>&1
grep -q "stiffness" three.txt && grep -qi "disagree" three.txt && ok || fail "disagreeing logs not named: $(cat three.txt)"
# The steady log: the stiffness is not determined (refused by name, exit 4).
expect 4 "stiffness" -- joint steady.txt "${flags[@]}"
# Irregular time stamps are refused, naming the jitter (never a silent 0 Hz cutoff).
awk '{ $1 = $1 + ((NR * 7) % 5) * 0.00001; print }' bench1.txt > jitter.txt
expect 3 "jitter" -- joint jitter.txt "${flags[@]}"
# Neither torque: named.
cut -d' ' -f1-3 bench1.txt > notorque.txt
expect 3 "needs the motor torque tau .* or the shaft torque tau_link" -- joint notorque.txt --no-header --delimiter space \
  --col 't=#1' --col 'q_motor=integral(#2)' --col 'q_link=integral(#3)' --params bench.yaml
finish
