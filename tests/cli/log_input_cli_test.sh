#!/usr/bin/env bash
# Logs as they come (docs/formats.md#logs) through the command line: a
# header-less, a semicolon and a blank-separated copy of a simulated axis log,
# positions in degrees read by an expression, two-file logs, --rate, crops,
# SysId JSON, `inspect`, the provenance and byte-identical reruns.
# Usage: log_input_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=cli_test_lib.sh
. "$src/tests/cli/cli_test_lib.sh"

"$bin" simulate axis --params "$src/data/axis_example.yaml" --noise 0.05 --seed 3 -o axis.csv || fail "simulate axis"
"$bin" axis axis.csv -q -o reference.yaml || fail "reference fit"
inertia() { awk '/^  inertia:/ {print $2}' "$1"; }
same() {  # same estimate within 1e-6 relative (degrees round-trip in the 10th digit)
  awk -v a="$(inertia "$1")" -v b="$(inertia reference.yaml)" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= 1e-6 * b) }'
}

# No header, positions in degrees, read back with an expression.
grep -v '^#' axis.csv | tail -n +2 | awk -F, '{ printf "%s,%.12g,%s\n", $1, $2 * 180 / 3.14159265358979324, $3 }' > bare.csv
"$bin" axis bare.csv --col t=#1 --col 'q=pi/180*#2' --col tau=#3 -q -o bare.yaml && same bare.yaml && ok ||
  fail "header-less log with a degree expression: inertia $(inertia bare.yaml) vs $(inertia reference.yaml)"
grep -q 'notes: \["no header row: the first row holds numbers (columns are #1 .. #n)", "t = #1", "q = pi/180\*#2", "tau = #3"\]' bare.yaml \
  && ok || fail "provenance of the expressions: $(grep 'file:' bare.yaml)"
# A constant in the expression (an encoder zero that is not the model's, as
# an MDH offset): the positions moved by it, the estimates unchanged.
"$bin" axis bare.csv --col t=#1 --col 'q=pi/180*#2 - pi/2' --col tau=#3 -q -o offset.yaml && same offset.yaml &&
  grep -q '"q = pi/180\*#2 - pi/2"' offset.yaml && ok || fail "a column expression with a constant: $(inertia offset.yaml)"
cp bare.yaml bare_first.yaml
"$bin" axis bare.csv --col t=#1 --col 'q=pi/180*#2' --col tau=#3 -q -o bare.yaml && cmp -s bare.yaml bare_first.yaml \
  && ok || fail "rerun of a header-less fit differs"
# A measured rate (--col qd=...) instead of differentiating q: a central
# difference of q as the "velocity sensor"; the inertia stays within 5 %.
awk -F, 'NR > 1 { t[NR] = $1; q[NR] = $2; u[NR] = $3 } END { for (k = 3; k < NR; ++k)
  printf "%s,%s,%s,%.12g\n", t[k], q[k], u[k], (q[k + 1] - q[k - 1]) / (t[k + 1] - t[k - 1]) }' <(grep -v '^#' axis.csv) > rate.csv
"$bin" axis rate.csv --col t=#1 --col q=#2 --col tau=#3 --col qd=#4 -q -o rate.yaml &&
  awk -v a="$(inertia rate.yaml)" -v b="$(inertia reference.yaml)" 'BEGIN { exit !(a > 0.95 * b && a < 1.05 * b) }' &&
  grep -q '"qd = #4"' rate.yaml && ok || fail "measured rate: inertia $(inertia rate.yaml) vs $(inertia reference.yaml)"
# Semicolons and blanks, detected.
grep -v '^#' axis.csv | tr ',' ';' > semicolon.csv
"$bin" axis semicolon.csv -q -o semicolon.yaml && same semicolon.yaml && ok || fail "semicolon-separated log"
grep -v '^#' axis.csv | tr ',' ' ' > blanks.txt
"$bin" axis blanks.txt -q -o blanks.yaml && same blanks.yaml && ok || fail "blank-separated log"
# Two files row by row; positions count on.
cut -d, -f1,2 bare.csv > positions.csv
cut -d, -f3 bare.csv > torques.csv
"$bin" axis positions.csv --join torques.csv --col t=#1 --col 'q=pi/180*#2' --col tau=#3 -q -o joined.yaml &&
  same joined.yaml && ok || fail "joined log"
grep -q "joined with torques.csv (sha256 " joined.yaml && ok || fail "join not in the provenance"
head -5 torques.csv > short.csv
expect 3 "positions.csv: [0-9]+ rows, but short.csv \(joined with --join\) has 5" -- \
  axis positions.csv --join short.csv --col t=#1 --col q=#2 --col tau=#3
# A torque logged by another device: 500 Hz, stamped in ms on a clock that
# starts at 1000 s and runs 200 ppm fast, from t = 0.3 s; it records the
# encoder too. Joined by time and aligned by that channel, the clock-rate
# difference is found and the inertia stays within 0.5 % of the one-file fit.
grep -v '^#' axis.csv | awk -F, 'NR == 1 { print "t,q" > "p.csv"; print "stamp_ms,torque,enc" > "u.csv"; next }
  { print $1 "," $2 > "p.csv"; if (NR % 2 == 0 && $1 >= 0.3) printf "%.4f,%s,%s\n", (1000 + ($1 - 0.3) * 1.0002) * 1e3, $3, $2 > "u.csv" }'
"$bin" axis p.csv --join u.csv --join-time stamp_ms/1000 --join-align q=enc --col tau=torque -q -o clocks.yaml &&
  awk -v a="$(inertia clocks.yaml)" -v b="$(inertia reference.yaml)" 'BEGIN { exit !(a > 0.995 * b && a < 1.005 * b) }' &&
  grep -q "u.csv: aligned by cross-correlation: shift -999.7" clocks.yaml &&
  grep -Eq "u.csv: the clocks run at different rates: .* \(-(19[5-9]|20[0-5])\.[0-9] ppm\), corrected linearly" clocks.yaml &&
  grep -q "9700 of 10001 samples kept (0.3 .. 9.999 s), where u.csv has data" clocks.yaml && ok ||
  fail "joined by time: inertia $(inertia clocks.yaml) vs $(inertia reference.yaml); $(grep -o 'joined by time[^]]*' clocks.yaml)"
# The same with the shift given (a clock without the rate error).
awk -F, 'NR == 1 { print; next } { printf "%.4f,%s,%s\n", 1e6 + ($1 - 1e6) / 1.0002, $2, $3 }' u.csv > v.csv
"$bin" axis p.csv --join v.csv --join-time stamp_ms/1000 --join-shift -999.7 --col tau=torque -q -o shifted.yaml &&
  awk -v a="$(inertia shifted.yaml)" -v b="$(inertia reference.yaml)" 'BEGIN { exit !(a > 0.995 * b && a < 1.005 * b) }' &&
  grep -q "v.csv: shifted by -999.7 s (--join-shift)" shifted.yaml && ok || fail "joined by time with --join-shift"
expect 2 "--join-time, --join-shift and --join-align apply to a file given with --join" -- \
  axis p.csv --join-time stamp_ms/1000
expect 2 "--join v.csv: a shift or an alignment joins by time: give the joined file's time column with --join-time" -- \
  axis p.csv --join v.csv --join-shift 3 --col tau=torque
expect 3 "p.csv: the log spans 0 .. 10 s, v.csv spans 1300 .. 1309.7 s on its clock: they do not overlap" -- \
  axis p.csv --join v.csv --join-time stamp_ms/1000 --join-shift 300 --col tau=torque
# A derived time base is refused as such (issue 36: it said "time not strictly increasing").
printf 't,q,tau,one\n0,0,1,1\n0.001,0.1,1,1\n0.002,0.2,1,1\n' > derived_time.csv
expect 2 "--col t=integral\(one\): the time base cannot be derived" -- axis derived_time.csv --col 't=integral(one)'
# No time column: --rate (the simulated log is 1 kHz).
cut -d, -f2,3 bare.csv > untimed.csv
"$bin" axis untimed.csv --rate 1000 --col 'q=pi/180*#1' --col tau=#2 -q -o untimed.yaml && same untimed.yaml && ok ||
  fail "--rate: inertia $(inertia untimed.yaml)"
expect 2 "--rate: axis.csv has a time column 't'" -- axis axis.csv --rate 1000
# Crops: fewer samples, recorded.
"$bin" axis axis.csv --from 2 --to 6 -q -o cropped.yaml && grep -q "samples: 4001, notes: \[\"cropped to 2 .. 6 s" cropped.yaml \
  && ok || fail "crop: $(grep 'file:' cropped.yaml)"
expect 3 "axis.csv: no samples between --from 50 s and --to 60 s" -- axis axis.csv --from 50 --to 60
expect 2 "--from 6 --to 2: need from < to" -- axis axis.csv --from 6 --to 2
# Refusals name the file and line, or the option.
sed '7s/,[^,]*$/,x7/' bare.csv > bad.csv
expect 3 "bad.csv:7: column #3: not a number: \"x7\"" -- axis bad.csv --col t=#1 --col q=#2 --col tau=#3
expect 3 "bare.csv: missing columns 't', 'q', 'tau' or 'i' \(the file has no header: name its 3 columns by position" -- axis bare.csv
expect 2 "--col q=#2\*#3: two columns" -- axis bare.csv --col t=#1 --col 'q=#2*#3' --col tau=#1
expect 2 "--col q=2\*degrees: 'degrees' is neither a column" -- axis bare.csv --col t=#1 --col 'q=2*degrees' --col tau=#3
# SysId JSON: the four tests are logs; a drivetrain needs a side.
# The velocity column (rotations/s) by central differences of q.
awk -F, 'NR > 1 && !/^#/ { n++; t[n] = $1; q[n] = $2; u[n] = $3 }
  END { r = 6.283185307179586
        for (k = 1; k <= n; k++) { a = k > 1 ? k - 1 : k; b = k < n ? k + 1 : k
          s = s (k > 1 ? ", " : "") sprintf("[%s, %s, %.12g, %.12g]", t[k], u[k], q[k] / r, (q[b] - q[a]) / (t[b] - t[a]) / r) }
        printf "{\"test\": \"Simple\", \"units\": \"Radians\", \"unitsPerRotation\": 6.283185307179586, \"slow-forward\": [%s], \"slow-backward\": [%s], \"fast-forward\": [%s], \"fast-backward\": [%s]}\n", s, s, s, s }' \
  <(grep -v '^#' axis.csv) > sysid.json
"$bin" inspect sysid.json > inspect.txt && grep -q "sysid.json \[slow-forward\] (sysid)" inspect.txt && ok ||
  fail "inspect of a SysId file: $(head -3 inspect.txt)"
# Fitted from SysId logs (the logged velocity as qd), the feed-forward
# section holds SysId's gains in its units (docs/models.md#feed-forward).
"$bin" axis sysid.json -q -o sysid.yaml 2> /dev/null
grep -q '^  effort_unit: "V"' sysid.yaml && grep -q "^  Ks: {value: 0\.9[0-9]*, std: .*# V$" sysid.yaml &&
  grep -q "^  Kv: {value: 0\.[12][0-9]*, .*# V s/Radians$" sysid.yaml && grep -q "^  Ka: {value: 0\.0[45].*# V s^2/Radians" sysid.yaml &&
  grep -q "^  offset: {value: 0\.[23].*# V$" sysid.yaml && ok || fail "SysId gains: $(grep -A7 'feedforward:' sysid.yaml)"
[ "$(grep -c 'segment: "' sysid.yaml)" -eq 4 ] && ok || fail "SysId provenance: one entry per test expected"
cp sysid.yaml sysid_first.yaml
"$bin" axis sysid.json -q -o sysid.yaml 2> /dev/null && cmp -s sysid.yaml sysid_first.yaml && ok || fail "SysId rerun differs"
# An Arm test logged in Rotations (what SysIdRoutine writes) is converted
# to Radians, not refused: its gains equal those of the same test logged in
# Radians (to the 12 digits the JSON holds), with a note (the first 1200
# samples: an arm fit of the whole log takes 37 s, 150 s under the sanitizers).
arm_json() {  # UNITS ROTATIONS_PER_RADIAN_OF_THE_CSV UNITS_PER_ROTATION
  awk -F, -v units="$1" -v r="$2" -v per="$3" 'NR > 1 && NR <= 1200 && !/^#/ { n++; t[n] = $1; q[n] = $2; u[n] = $3 }
    END { for (k = 1; k <= n; k++) { a = k > 1 ? k - 1 : k; b = k < n ? k + 1 : k
            s = s (k > 1 ? ", " : "") sprintf("[%s, %s, %.12g, %.12g]", t[k], u[k], q[k] / r, (q[b] - q[a]) / (t[b] - t[a]) / r) }
          printf "{\"test\": \"Arm\", \"units\": \"%s\", \"unitsPerRotation\": %s, \"slow-forward\": [%s], \"slow-backward\": [%s], \"fast-forward\": [%s], \"fast-backward\": [%s]}\n", units, per, s, s, s, s }' \
    <(grep -v '^#' axis.csv)
}
arm_json Radians 6.283185307179586 6.283185307179586 > arm_radians.json  # SysId JSON holds rotations
arm_json Rotations 6.283185307179586 1 > arm_rotations.json
# An Arm test fits gravity by default (issue 37); an Elevator's Kg is the offset.
"$bin" axis arm_radians.json -o arm_radians.yaml > arm.txt 2>&1 && grep -q "^    gravity_cos: {value: " arm_radians.yaml &&
  grep -q "^  Kg: {value: " arm_radians.yaml && grep -q "SysId Arm test: gravity Kg cos(q - Kg_angle) fitted" arm.txt && ok ||
  fail "SysId Arm: $(cat arm.txt)"
"$bin" axis arm_rotations.json -o arm_rotations.yaml > arm_rotations.txt 2>&1 &&
  grep -q "SysId Arm test logged in Rotations: converted to Radians (q and q' x 6.28319)" arm_rotations.txt &&
  grep -q '^  position_unit: "Radians"' arm_rotations.yaml && ok || fail "SysId Arm in Rotations: $(head -c 600 arm_rotations.txt)"
for key in Kv Ka Kg Ks; do
  a=$(sed -n "s/^  $key: {value: \([^,]*\),.*/\1/p" arm_radians.yaml); b=$(sed -n "s/^  $key: {value: \([^,]*\),.*/\1/p" arm_rotations.yaml)
  awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; if (d < 0) d = -d; m = a < 0 ? -a : a; exit !(a != "" && d <= 1e-6 * m) }' && ok ||
    fail "SysId Arm: $key in Radians $a, from Rotations $b"
done
sed 's/"Simple"/"Elevator"/' sysid.json > elevator.json
"$bin" axis elevator.json -o elevator.yaml > elevator.txt 2>&1 && grep -q "SysId Elevator test: the constant gravity Kg is the offset" elevator.txt &&
  ! grep -q "gravity_cos: {value" elevator.yaml && ok || fail "SysId Elevator: $(cat elevator.txt)"
# Position and velocity held for 4 rows (a status frame read by a faster
# logger): fitted by output error at the frames, the frames' timing in the
# intervals (docs/models.md#status-frames).
awk -F, 'NR > 1 && !/^#/ { n++; t[n] = $1; q[n] = $2; u[n] = $3 }
  END { r = 6.283185307179586
        for (k = 1; k <= n; k++) { h = k - (k - 1) % 4; a = h > 1 ? h - 1 : h; b = h < n ? h + 1 : h
          s = s (k > 1 ? ", " : "") sprintf("[%s, %s, %.12g, %.12g]", t[k], u[k], q[h] / r, (q[b] - q[a]) / (t[b] - t[a]) / r) }
        printf "{\"test\": \"Simple\", \"units\": \"Radians\", \"unitsPerRotation\": 6.283185307179586, \"slow-forward\": [%s], \"slow-backward\": [%s], \"fast-forward\": [%s], \"fast-backward\": [%s]}\n", s, s, s, s }' \
  <(grep -v '^#' axis.csv) > held.json
"$bin" axis held.json -o held.yaml > held.txt 2>&1 && grep -q "^status frames: the position of 4 of 4 logs repeats between frames every 4 ms" held.txt &&
  grep -q "^method: output error (auto: status frames" held.txt && grep -q "^systematic errors in the intervals" held.txt && ok ||
  fail "status frames not fitted at the frames: $(grep -i 'status\|method' held.txt | head -3)"
# The advice of the processing warning (output error) is tried before it is printed.
"$bin" axis held.json --method idim -o held_idim.yaml > held_idim.txt 2>&1
grep -q "or --method oe, which does not differentiate; tried: output error gives inertia = [0-9.e-]* +- [0-9.e-]*, " held_idim.txt && ok ||
  fail "output-error advice not tried: $(grep 'warning: processing' held_idim.txt)"
"$bin" axis sysid.json -o own_rate.yaml > own_rate.txt 2>&1 && grep -q "^adequacy" own_rate.txt && ! grep -q "status frames" own_rate.txt &&
  ok || fail "a log at its own rate warned of status frames: $(grep -i warning own_rate.txt | head -3)"
sed 's/"Simple"/"Drivetrain"/' sysid.json > drive.json
expect 2 "drive.json: a SysId Drivetrain file: give --side left, right or both" -- axis drive.json
# Hostile text and numbers (issues 21, 36): units with a line break and a
# key, or with Java's \u escapes that would close a comment in the exported
# class (\u002a/static{System.exit(7);}/\u002a), are refused naming 'units';
# a unitsPerRotation that overflows is named; columns beyond what a fit can
# square are refused naming the column and its range.
sed 's/"units": "Radians"/"units": "Rad\\n  Kg: {value: 99, std: 0}"/' sysid.json > units.json
expect 3 "units.json: 'units': not a unit name: a byte that is not printable ASCII" -- axis units.json
sed 's|"units": "Radians"|"units": "\\\\u002a/static{System.exit(7);}/\\\\u002a"|' sysid.json > java_units.json
grep -q '"units": "\\\\u002a/static' java_units.json && ok || fail "java_units.json not made: $(head -c 120 java_units.json)"
expect 3 "java_units.json: 'units': not a unit name: the character '.'" -- axis java_units.json
# A log in radians is not a linear axis (WPILib's units library would reject the export).
expect 2 "--linear: the log's position unit is 'Radians', an angle" -- axis sysid.json --linear
sed 's/"unitsPerRotation": 6.283185307179586/"unitsPerRotation": 1e308/' sysid.json > per_rotation.json
expect 3 "per_rotation.json: unitsPerRotation = 1e\+308: slow-forward\[[0-9]+\] (position|velocity) x unitsPerRotation overflows" -- \
  axis per_rotation.json
awk -F, 'NR > 1 { printf "%s,%s,%.6g\n", $1, $2, $3 * 8e306 }' bare.csv > huge.csv
expect 3 "huge.csv: column 'tau': values up to [0-9.e+]+ in magnitude, outside 1e-150 .. 1e\+150" -- \
  axis huge.csv --col t=#1 --col 'q=pi/180*#2' --col tau=#3
expect 3 "bare.csv: column 'tau': values up to [0-9.e-]+ in magnitude, outside 1e-150" -- \
  axis bare.csv --col t=#1 --col 'q=pi/180*#2' --col 'tau=1e-300*#3'
expect 3 "bare.csv: column 'tau': values up to" -- axis bare.csv --col t=#1 --col 'q=pi/180*#2' --col 'tau=1e300*#3'
# The MAT reader's process dies with the tool, however the tool ends
# (issue 21): a v7.3 file on which HDF5 spins keeps the reader busy.
tail -c +2 "$src/tests/fuzz/regressions/log_input_mat73_spin.bin" > spin_reader_$$.mat
command -v pgrep > /dev/null || echo "skipped: the MAT reader's lifetime (no pgrep; install procps)"
for how in $(command -v pgrep > /dev/null && echo TERM KILL timeout); do
  if [ $how = timeout ]; then
    timeout -s TERM 1 "$bin" inspect spin_reader_$$.mat > /dev/null 2>&1
  else
    "$bin" inspect spin_reader_$$.mat > /dev/null 2>&1 &
    pid=$!
    for _ in 1 2 3 4 5 6 7 8 9 10; do pgrep -P $pid > /dev/null && break; sleep 0.1; done
    pgrep -P $pid > /dev/null || fail "no MAT reader process seen under $pid"
    kill -$how $pid
    wait $pid 2> /dev/null
  fi
  sleep 0.3
  if pgrep -f "spin_reader_$$.mat" > /dev/null; then
    fail "the MAT reader outlived the tool ($how)"
    pkill -KILL -f "spin_reader_$$.mat"
  else
    ok
  fi
done
# A torque of zeros or a constant: nothing to identify (exit 4 naming it), whatever the method.
awk -F, '{ printf "%s,%s,%s\n", $1, $2, ($1 == "t" ? "tau" : 0) }' <(grep -v '^#' axis.csv) > zeros.csv
for method in idim oe auto; do
  expect 4 "nothing to identify: the measured zeros.csv:tau \(0 throughout\) does not vary" -- axis zeros.csv --method $method
done
# A log whose torque does not vary: its fit % means nothing (n/a, null), not -3.6e16.
awk -F, '{ printf "%s,%s,%s\n", $1, $2, ($1 == "t" ? "tau" : 0.5) }' <(grep -v '^#' axis.csv) > constant.csv
"$bin" validate reference.yaml constant.csv --json > constant.json 2> stderr.txt && grep -q '"fit_percent":null' constant.json &&
  "$bin" validate reference.yaml constant.csv > constant.txt 2>&1 && grep -q " n/a " constant.txt && ok ||
  fail "validate of a constant torque: $(cat constant.json constant.txt stderr.txt)"
# Nearly constant (std 0.7 % of the level, like a held voltage step): no fit % either, and no "low fit" warning.
awk -F, '{ printf "%s,%s,%s\n", $1, $2, ($1 == "t" ? "tau" : 0.5 + 0.005 * sin(NR)) }' <(grep -v '^#' axis.csv) > held.csv
"$bin" validate reference.yaml held.csv --json > held.json 2> stderr.txt && grep -q '"fit_percent":null' held.json &&
  ! grep -q "low fit" stderr.txt && ok || fail "validate of a nearly constant torque: $(cat held.json stderr.txt)"
# SysId JSON is streamed (issue 21): 17 MB of samples read within 120 MB of
# address space (a DOM took 23 times the file); a byte-order mark is read;
# a key given twice and --side on a CSV are refused.
awk 'BEGIN { srand(1); n = 100000; printf "{\"test\": \"Simple\", \"units\": \"Radians\", \"unitsPerRotation\": 1"
  split("slow-forward slow-backward fast-forward fast-backward", T, " ")
  for (j = 1; j <= 4; j++) { printf ", \"%s\": [", T[j]
    for (k = 0; k < n; k++) printf "%s[%.4f, %.6f, %.6f, %.6f]", (k ? ", " : ""), k * 0.005, 1 + rand(), k * 0.001, 0.2 + rand() * 0.01
    printf "]" }
  printf "}\n" }' > big_sysid.json
if sanitized; then
  echo "skipped: SysId memory under AddressSanitizer (its shadow memory needs the address space)"
else
  ( ulimit -v 120000; "$bin" inspect big_sysid.json > big_inspect.txt 2> stderr.txt ) &&
    grep -q "100000 samples" big_inspect.txt && ok || fail "SysId 17 MB within 120 MB: $(cat stderr.txt)"
fi
{ printf '\xef\xbb\xbf'; cat sysid.json; } > bom.json
"$bin" inspect bom.json > inspect.txt 2> stderr.txt && grep -q "bom.json \[slow-forward\] (sysid)" inspect.txt && ok ||
  fail "SysId with a byte-order mark: $(head -3 inspect.txt) $(cat stderr.txt)"
sed 's/"units": "Radians"/"units": "Radians", "unitsPerRotation": 1/' sysid.json > twice.json
expect 3 "twice.json: key 'unitsPerRotation' appears twice" -- axis twice.json
expect 2 "--side left: bare.csv is a CSV file; --side applies to SysId Drivetrain files" -- \
  axis bare.csv --col t=#1 --col q=#2 --col tau=#3 --side left
# inspect: columns, rate, and the columns as a fit reads them.
"$bin" inspect bare.csv --col t=#1 --col 'q=pi/180*#2' > inspect.txt && grep -q "10001 samples, t = 0 .. 10 s (10 s), rate 1000 Hz" inspect.txt \
  && grep -q "q = pi/180\*#2" inspect.txt && ok || fail "inspect: $(cat inspect.txt)"
finish
