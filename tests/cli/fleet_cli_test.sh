#!/usr/bin/env bash
# A fleet in CI (docs/guide.md#fleets-and-drift): 200 nightly axis logs as a
# joint_states-style CSV (time, position, effort), 15 axes whose friction
# drifted (+30 % viscous, +25 % Coulomb), two broken logs. The README's
# batch line (--col before the logs) fits all 200; summary.csv parses as
# RFC 4180 with a unique header and numbers in the parameter cells, and
# agrees with the per-log files; `compare --fail-above 10` exits 1 and
# flags exactly the 15 drifted axes; progress is reported without a terminal.
# Usage: fleet_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=cli_test_lib.sh
. "$src/tests/cli/cli_test_lib.sh"

mkdir logs
printf 'axis:\n  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1.0\n  offset: 0.3\n' > nominal.yaml
printf 'axis:\n  inertia: 0.05\n  viscous: 0.26\n  coulomb: 1.25\n  offset: 0.3\n' > drifted.yaml
joint_states() {  # simulate PARAMS SEED OUT: time,position,effort at 250 Hz
  "$bin" simulate axis --params "$1" --rate 250 --duration 8 --noise 0.05 --seed "$2" -o sim.csv > /dev/null &&
    awk -F, '/^#/ || /^t,/ { next } BEGIN { print "time,position,effort" } { print $1 "," $2 "," $3 }' sim.csv > "$3"
}
drifted_list=""
for i in $(seq 200); do
  name=$(printf 'logs/axis_%03d.csv' "$i")
  if [ $((i % 13)) -eq 0 ]; then
    joint_states drifted.yaml "$i" "$name" || fail "simulate $i"
    drifted_list="$drifted_list $name"
  else
    joint_states nominal.yaml "$i" "$name" || fail "simulate $i"
  fi
done
printf 'time,position,effort\n' > logs/broken_header.csv
printf 'time,position,effort\n0,0,1\n0.004,x,1\n' > logs/broken_number.csv
joint_states nominal.yaml 1000 base.csv && "$bin" axis --col t=time --col q=position --col tau=effort base.csv -q -o base.yaml ||
  fail "base fit"

# The README's batch line: --col before the logs, and progress without a terminal.
"$src/scripts/batch-fit" -o out -j 2 --progress 1 "$bin" axis --col t=time --col q=position --col tau=effort \
  ::: logs/*.csv 2> batch.err
code=$?
[ "$code" -eq 5 ] && ok || fail "batch-fit exit $code, expected 5 (two broken logs): $(tail -3 batch.err)"
[ "$(ls out/*.yaml 2> /dev/null | wc -l)" -eq 200 ] && ok || fail "$(ls out/*.yaml | wc -l) parameter files, expected 200"
grep -q "^batch-fit: [0-9]* of 202 logs done" batch.err && ok || fail "no progress lines without a terminal: $(head -3 batch.err)"

# Spread by GNU parallel's ssh logins (":" is this machine): the same summary.
printf ':\n' > hosts
"$src/scripts/batch-fit" -o local -j 2 "$bin" axis --col t=time --col q=position --col tau=effort ::: logs/axis_00[1-4].csv 2> /dev/null
"$src/scripts/batch-fit" -o spread --sshloginfile hosts "$bin" axis --col t=time --col q=position --col tau=effort \
  ::: logs/axis_00[1-4].csv 2> /dev/null
cmp -s local/summary.csv spread/summary.csv && [ "$(wc -l < spread/summary.csv)" -eq 5 ] && ok ||
  fail "summary over --sshloginfile differs: $(diff local/summary.csv spread/summary.csv | head -3)"

# A summary.csv that is not a regular file is not replaced (exit 2, named).
mkdir -p guarded/summary.csv/keep
"$src/scripts/batch-fit" -o guarded "$bin" axis --col t=time --col q=position --col tau=effort ::: logs/axis_001.csv 2> guarded.err
code=$?
[ "$code" -eq 2 ] && [ -d guarded/summary.csv/keep ] && grep -q "summary.csv is not a regular file" guarded.err && ok ||
  fail "batch-fit over a directory summary.csv: exit $code, $(cat guarded.err)"

# summary.csv as a CSV reader sees it (RFC 4180: quoted fields, "" inside).
awk '
  function parse(line,    n, field, i, c, quoted) {
    n = 0; field = ""; quoted = 0
    for (i = 1; i <= length(line); i++) {
      c = substr(line, i, 1)
      if (quoted) { if (c == "\"") { if (substr(line, i + 1, 1) == "\"") { field = field c; i++ } else quoted = 0 } else field = field c }
      else if (c == "\"") quoted = 1
      else if (c == ",") { cell[++n] = field; field = "" }
      else field = field c
    }
    cell[++n] = field
    return n
  }
  NR == 1 { columns = parse($0); for (i = 1; i <= columns; i++) { if (cell[i] in seen) { print "duplicate column " cell[i]; bad = 1 }; seen[cell[i]] = 1; head[i] = cell[i] }; next }
  { n = parse($0); rows++
    if (n != columns) { print "row " NR ": " n " fields, header has " columns; bad = 1 }
    if (cell[2] == 0) { ok_rows++
      for (i = 4; i < columns - 1; i++) if (cell[i] !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) { print "row " NR " " head[i] ": not a number: " cell[i]; bad = 1 } }
    else if (cell[columns - 1] == "") { print "row " NR ": failed without a message"; bad = 1 }
    if (cell[columns] !~ /\.yaml$/) { print "row " NR ": no output file named"; bad = 1 } }
  END { if (rows != 202 || ok_rows != 200) { print rows " rows, " ok_rows " fitted"; bad = 1 }; exit bad }' out/summary.csv > csv.txt &&
  ok || fail "summary.csv: $(head -3 csv.txt)"
head -1 out/summary.csv | grep -q '^file,exit_code,fit_percent,inertia,inertia_std,viscous,viscous_std,coulomb,coulomb_std,offset,offset_std,message,output$' &&
  ok || fail "summary header: $(head -1 out/summary.csv)"
if command -v python3 > /dev/null && python3 -c 'import csv' 2> /dev/null; then
  python3 - out/summary.csv << 'PY' && ok || fail "python csv reader"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
assert len(rows) == 202, len(rows)
fitted = [r for r in rows if r["exit_code"] == "0"]
assert len(fitted) == 200
for r in fitted:
    for k in ("inertia", "viscous", "coulomb", "offset", "inertia_std"):
        float(r[k])
PY
fi
# The summary agrees with the per-log file (axis_007's viscous).
from_file=$(awk '/^fit:/ { f = 1 } f && /^    viscous: \{value:/ { gsub(/[{},]/, " "); print $3; exit }' out/logs_axis_007.yaml)
from_csv=$(awk -F, '$1 == "\"logs/axis_007.csv\"" { print $6 }' out/summary.csv)
[ -n "$from_file" ] && [ "$from_file" = "$from_csv" ] && ok || fail "summary viscous $from_csv vs file $from_file"

# compare: exactly the drifted axes, exit 1.
"$bin" compare base.yaml out/*.yaml --fail-above 10 --json > compare.json 2> compare.err
code=$?
[ "$code" -eq 1 ] && ok || fail "compare exit $code, expected 1: $(cat compare.err)"
flagged=$(grep -o '"file":"[^"]*","drift":true' compare.json | sed 's/"file":"out\/logs_\(axis_[0-9]*\)\.yaml".*/\1/' | sort | tr '\n' ' ')
expected=$(for f in $drifted_list; do basename "$f" .csv; done | sort | tr '\n' ' ')
[ "$flagged" = "$expected" ] && ok || fail "flagged [$flagged], expected [$expected]"
grep -q '"relative_change":' compare.json && grep -q '"z":' compare.json && ok || fail "compare json lacks relative_change / z"
# No drift among the nominal ones: exit 0; a parameter the base lacks: exit 3, named.
"$bin" compare base.yaml out/logs_axis_001.yaml out/logs_axis_002.yaml --fail-above 10 > /dev/null && ok || fail "nominal logs drifted"
# A gate that cannot judge fails (exit 1) and says why: a file without the estimate.
grep -v "^    offset: {value" out/logs_axis_001.yaml > no_offset.yaml
"$bin" compare base.yaml no_offset.yaml --fail-above 10 > /dev/null 2> undecided.err
[ $? -eq 1 ] && grep -q "the gate cannot judge no_offset.yaml: offset: the file has no estimate of it" undecided.err && ok ||
  fail "a gate that cannot judge passed: $(cat undecided.err)"
"$bin" compare base.yaml out/logs_axis_001.yaml --parameters stiffness > /dev/null 2> unknown.err
code=$?
[ "$code" -eq 3 ] && grep -q "^drivetrain-fit: --parameters: the base has no estimate of stiffness" unknown.err && ok ||
  fail "unknown parameter: exit $code, $(cat unknown.err)"
# --plot onto one of the compared files is refused (exit 2), the file kept (issue 55).
cp base.yaml base.png
"$bin" compare base.png out/logs_axis_001.yaml --plot base.png > /dev/null 2> plot_self.err
code=$?
[ "$code" -eq 2 ] && grep -q "is an input of this run" plot_self.err && cmp -s base.png base.yaml && ok ||
  fail "compare --plot onto its base: exit $code, $(cat plot_self.err)"
# report --fitted beside an axis: the two fits compared; a file without a fit refused by name.
"$bin" report base.yaml --fitted out/logs_axis_013.yaml > fitted.txt 2>&1 && grep -q "^out/logs_axis_013.yaml$" fitted.txt &&
  grep -q "^  viscous .*%" fitted.txt && ok || fail "report --fitted of an axis: $(cat fitted.txt)"
"$bin" report base.yaml --fitted nominal.yaml > nofit.txt 2>&1
code=$?
[ "$code" -eq 3 ] && grep -q "^drivetrain-fit: --fitted: nominal.yaml has no fit.estimates" nofit.txt && ok ||
  fail "report --fitted without a fit: exit $code, $(cat nofit.txt)"
# validate --fail-below: a quality gate, exit 1 after the table.
"$bin" validate base.yaml logs/axis_001.csv --col t=time --col q=position --col tau=effort --fail-below 50 > gate.txt 2>&1 &&
  ok || fail "validate --fail-below 50: $(tail -2 gate.txt)"
"$bin" validate base.yaml logs/axis_001.csv --col t=time --col q=position --col tau=effort --fail-below 99.999 > gate.txt 2> gate.err
code=$?
[ "$code" -eq 1 ] && grep -q "^drivetrain-fit: fit below 99.999 %: " gate.err && grep -q "axis_001" gate.txt && ok ||
  fail "validate --fail-below 99.999: exit $code, $(cat gate.err)"
finish
