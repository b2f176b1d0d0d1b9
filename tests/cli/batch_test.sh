#!/usr/bin/env bash
# scripts/batch-fit over 200 simulated step logs and 5 broken ones (issue 5):
# 200 parameter files, a 205-row summary with the 5 failures recorded.
# Usage: batch_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failed=0
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
mkdir logs
for seed in $(seq 200); do
  "$bin" simulate step --params "$src/data/paper000.yaml" --noise 0.1 --seed "$seed" -o "logs/step_$seed.csv" || fail "simulate $seed"
done
printf '' > logs/broken_empty.csv
printf 't,tau_motor,tau_link\n' > logs/broken_header.csv
printf 't,tau_motor,tau_link\n0,0,x\n' > logs/broken_number.csv
printf 't,tau_motor\n0,0\n' > logs/broken_column.csv
printf 't,tau_motor,tau_link\n0,0,0\n0.001,0,0\n0.002,0,0\n' > logs/broken_nostep.csv
"$src/scripts/batch-fit" -o out -j 2 "$bin" step --params "$src/data/paper000_start.yaml" ::: logs/*.csv
code=$?
[ "$code" -eq 5 ] || fail "batch-fit exit $code, expected 5 (some logs failed)"
[ "$(ls out/*.yaml | wc -l)" -eq 200 ] || fail "$(ls out/*.yaml | wc -l) parameter files, expected 200"
[ "$(($(wc -l < out/summary.csv) - 1))" -eq 205 ] || fail "summary has $(($(wc -l < out/summary.csv) - 1)) rows, expected 205"
[ "$(awk -F, 'NR > 1 && $2 != 0' out/summary.csv | wc -l)" -eq 5 ] || fail "summary does not record 5 failures"
[ "$(awk -F, 'NR > 1 && $2 == 4' out/summary.csv | wc -l)" -eq 1 ] || fail "the no-step log is not recorded with exit 4"
awk -F, 'NR > 1 && $2 == 0 && ($4 < 0.0155 || $4 > 0.0165) { bad++ } END { exit bad > 0 }' out/summary.csv \
  || fail "a fitted d_g in the summary is more than 3 % off"
[ "$(head -1 out/summary.csv)" = "file,exit_code,fit_percent,d_g,d_g_std,Theta_motor,Theta_motor_std,tau_c,tau_c_std,message" ] \
  || fail "summary header: $(head -1 out/summary.csv)"
if [ "$failed" -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, $failed failed"; exit 1; fi
