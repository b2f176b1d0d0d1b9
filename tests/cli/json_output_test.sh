#!/usr/bin/env bash
# Every subcommand's --json prints exactly one valid JSON document on stdout,
# for every parameter-file section combination of the reports.
# Usage: json_output_test.sh DRIVETRAIN_FIT CDRIVE_FIT JSON_CHECK SRC
set -u
dfit="$1"
cfit="$2"
check="$3"
src="$4"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0
# json NAME -- COMMAND...: runs it (exit 0 expected), parses its stdout.
json() {
  local name="$1"
  shift 2
  if ! "$@" > "$name.json" 2> "$name.err"; then
    echo "FAIL: $name: exit $? ($(head -c 300 "$name.err"))"
    failed=$((failed + 1))
  elif ! "$check" "$name.json"; then
    echo "FAIL: $name: not one JSON document: $(head -c 300 "$name.json")"
    failed=$((failed + 1))
  else
    passed=$((passed + 1))
  fi
}
D="$src/data"
"$dfit" simulate axis --params "$D/axis_example.yaml" --noise 0.05 -o axis.csv
cat "$D/paper000.yaml" "$D/robot_paper000.yaml" | grep -v '^#' > both.yaml

json step -- "$dfit" step "$D/fig6_step.csv" --params "$D/paper000_start.yaml" --json -o step.yaml
json step_stdout -- "$dfit" step "$D/fig6_step.csv" --params "$D/paper000_start.yaml" --json -o step2.yaml -q
json axis -- "$dfit" axis axis.csv --json -o axis.yaml
json robot -- "$dfit" robot "$D/robot_triangle.csv" --params "$D/robot_start.yaml" --json -o robot.yaml
json report_drivetrain -- "$dfit" report "$D/paper000.yaml" --json
json report_fitted -- "$dfit" report "$D/paper000.yaml" --fitted step.yaml --json
json report_robot -- "$dfit" report "$D/robot_paper000.yaml" --json
json report_both -- "$dfit" report both.yaml --json
json friction -- "$cfit" friction "$D/cdrive_slow_translation.csv" "$D/cdrive_slow_rotation.csv" \
  "$D/cdrive_slow_helical.csv" --params "$D/cdrive_start.yaml" --json -o friction.yaml
json inertia -- "$cfit" inertia "$D/cdrive_fast_translation.csv" "$D/cdrive_fast_rotation.csv" \
  "$D/cdrive_fast_helical.csv" --params "$D/cdrive_table1.yaml" --free I_h,I_c --json -o inertia.yaml
json cdrive_report -- "$cfit" report "$D/cdrive_table1.yaml" --json
json cdrive_report_fitted -- "$cfit" report friction.yaml --json
json cdrive_simulate -- "$cfit" simulate --program translation --params "$D/cdrive_table1.yaml" --cycles 1 --json -o sim.csv
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
