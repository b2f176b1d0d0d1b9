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
[ "$(head -1 out/summary.csv)" = "file,exit_code,fit_percent,d_g,d_g_std,Theta_motor,Theta_motor_std,tau_c,tau_c_std,message,output" ] \
  || fail "summary header: $(head -1 out/summary.csv)"

# Every log one row and one distinct file (issue 55): colliding names, a
# log named .csv, names that look like options, formula cells, a newline
# and a tab in a name, a tool that exits 0 without writing, GNU parallel
# failing to start the jobs, a second run into the same folder.
mkdir hostile
for name in "a b.csv" a_b.csv x.csv x.txt d_x.csv .csv -x.csv --help.csv "=1+1.csv" "+1.csv" "@SUM(1).csv" \
  "$(printf 'new\nline.csv')" "$(printf 'tab\tbed.csv')"; do
  cp logs/step_1.csv "hostile/$name"
done
mkdir hostile/d && cp logs/step_1.csv hostile/d/x.csv
(cd hostile && "$src/scripts/batch-fit" -o ../h -j 2 "$bin" step --params "$src/data/paper000_start.yaml" ::: \
  *.csv x.txt .csv d/x.csv 2> ../h.err)
code=$?
[ "$code" -eq 0 ] || fail "hostile names: exit $code: $(tail -3 h.err)"
grep -q "14 of 14 logs fitted" h.err || fail "hostile names: $(tail -1 h.err)"
[ "$(ls -A h | grep -c '\.yaml$')" -eq 14 ] || fail "hostile names: $(ls -A h | grep -c '\.yaml$') files for 14 logs"
if command -v python3 > /dev/null; then
  python3 - h/summary.csv << 'PY' || fail "hostile summary"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
assert len(rows) == 14, len(rows)
outputs = [r["output"] for r in rows]
assert len(set(outputs)) == 14, outputs
files = [r["file"] for r in rows]
for r in rows:
    assert r["exit_code"] == "0", r
    for cell in (r["file"], r["output"]):
        assert cell[:1] not in "=+-@\t\r", cell   # a spreadsheet evaluates none
assert "'=1+1.csv" in files and "'-x.csv" in files and "new\nline.csv" in files and "tab\tbed.csv" in files, files
PY
fi
printf '#!/bin/sh\nexit 0\n' > liar && chmod +x liar
"$src/scripts/batch-fit" -o h ./liar step ::: logs/step_1.csv 2> liar.err
code=$?
[ "$code" -eq 5 ] && grep -q ',70,,"the tool exited 0 but wrote no logs_step_1.yaml"' h/summary.csv ||
  fail "a tool that writes nothing (into a folder that has the file from before): exit $code, $(cat h/summary.csv)"
"$src/scripts/batch-fit" -o lost --sshloginfile ':' "$bin" step ::: logs/step_1.csv logs/step_2.csv 2> lost.err
code=$?
[ "$code" -eq 5 ] && grep -q "0 of 2 logs fitted, 2 failed" lost.err && [ "$(grep -c ',255,' lost/summary.csv)" -eq 2 ] ||
  fail "jobs that never ran: exit $code, $(tail -1 lost.err)"
"$src/scripts/batch-fit" -o 2> usage.err
[ $? -eq 2 ] && grep -q "batch-fit: -o needs a value" usage.err || fail "-o without a value: $(cat usage.err)"
# The progress line's sleep does not hold stderr open after the work.
started=$(date +%s)
"$src/scripts/batch-fit" -o quick --progress 60 "$bin" step --params "$src/data/paper000_start.yaml" ::: logs/step_1.csv 2>&1 | cat > /dev/null
[ $(($(date +%s) - started)) -lt 30 ] || fail "batch-fit | cat waited for the progress sleep"
# --list with a binary (the tool's path taken as the list when --list has
# no value): refused at once (fuzz-options found a 240 s hang reading it).
started=$(date +%s)
"$src/scripts/batch-fit" -o binary_list --list "$bin" step ::: logs/step_1.csv > /dev/null 2> list.err
code=$?
[ "$code" -eq 2 ] && grep -q "not a list of paths" list.err && [ $(($(date +%s) - started)) -lt 10 ] ||
  fail "--list of a binary: exit $code after $(($(date +%s) - started)) s: $(cat list.err)"
if [ "$failed" -eq 0 ]; then echo "1 passed, 0 failed"; else echo "0 passed, $failed failed"; exit 1; fi
