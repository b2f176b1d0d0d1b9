#!/usr/bin/env bash
# WPILib DataLog (.wpilog) SysIdRoutine logs (docs/formats.md#wpilog), written
# by tests/support/wpilog_writer.py (independent of the reader): a simulated
# motor (Ks 0.25 V, Kv 2.5 V s/m, Ka 0.3 V s^2/m), logged at 50 Hz with
# jitter, noise and a quantised position, each entry at its own time, an
# aborted first quasistatic run, a second motor, a struct entry, retained
# values with negative timestamps.
#  - two motors: refused naming them (exit 2); --motor fits; every estimate
#    holds the truth in its interval; the feed-forward is in V and Meters;
#  - inspect lists the entries, the routine, the motors and the runs;
#  - round trip: with the entries at one time per loop, the fit of the
#    wpilog equals the fit of the four tests' CSVs to the last digit;
#  - a log cut inside a record is refused with its offset (exit 3);
#  - other names: a RobotPy-style log (its own entry names, no units) fits
#    with --entry to the estimates of SysIdRoutine's names, to the last
#    digit; without its state entry the tests are found from the voltage
#    (and the truth still held); an AdvantageKit-style log (enum state
#    names, ...AppliedVolts/PositionRad/VelocityRadPerSec) is recognised
#    without flags; inspect reads a log with no routine (exit 0, telling
#    how to name the entries); bad --entry values are refused by name.
# Usage: wpilog_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
source "$src/tests/cli/cli_test_lib.sh"
if ! command -v python3 > /dev/null; then
  echo "python3 not installed: the WPILog writer cannot run (skipped)"
  exit 0
fi
python3 "$src/tests/support/wpilog_writer.py" routine.wpilog || { echo "FAIL: writer"; exit 1; }

expect 2 "routine.wpilog: 2 motors \(leader, follower\): give --motor" -- axis routine.wpilog
expect 2 "--motor nobody: routine.wpilog has no such motor \(found: leader, follower\)" -- axis routine.wpilog --motor nobody
expect 2 "--mechanism Arm: routine.wpilog has no such SysIdRoutine \(found: Shooter\)" -- axis routine.wpilog --mechanism Arm

"$bin" axis routine.wpilog --motor leader -q -o fit.yaml 2> fit.err || fail "fit: $(cat fit.err)"
# holds FILE NAME=TRUTH...: each estimate's interval in FILE holds its truth.
holds() {
  local file=$1 pair name truth line low high
  shift
  for pair in "$@"; do
    name=${pair%=*}; truth=${pair#*=}
    line=$(grep "^    $name: {value" "$file")
    low=$(sed -n 's/.*ci95: \[\([^,]*\), .*/\1/p' <<< "$line"); high=$(sed -n 's/.*ci95: \[[^,]*, \([^]]*\)\].*/\1/p' <<< "$line")
    awk -v l="$low" -v h="$high" -v t="$truth" 'BEGIN { exit !(l != "" && l <= t && t <= h) }' && ok ||
      fail "$file: $name: [$low, $high] misses $truth"
  done
}
# Every estimate's interval holds the simulated truth.
holds fit.yaml inertia=0.3 viscous=2.5 coulomb=0.25 offset=0
grep -q 'Kv: {value: .*# V s/Meters' fit.yaml && ok || fail "feed-forward units: $(grep -A5 '^feedforward' fit.yaml)"
grep -q "run 2 of 2 (.*the test ran more than once: its last complete run is used" fit.yaml && ok ||
  fail "the rerun test's note: $(grep -m3 'run ' fit.yaml)"
grep -q "position was logged a median 15 µs after the voltage" fit.yaml && ok || fail "the alignment note"
# gains and the WPILib export take the fit.
"$bin" gains fit.yaml --loop velocity -o gains.yaml > /dev/null 2>&1 &&
  "$bin" export gains.yaml --to wpilib-java --joint shooter -o ShooterFeedforwardGains.java &&
  grep -q "Feedforward(kS" ShooterFeedforwardGains.java && ok || fail "gains and export of a wpilog fit"

"$bin" inspect routine.wpilog > inspect.txt 2> inspect.err || fail "inspect: $(cat inspect.err)"
grep -q "SysIdRoutine 'Shooter' (--mechanism): motors leader, follower (--motor)" inspect.txt &&
  grep -q "'Shooter' test quasistatic-forward: 2 runs" inspect.txt &&
  grep -q "NT:/SmartDashboard/retained .*2 with negative times left out" inspect.txt &&
  grep -q "1 of no started entry" inspect.txt && ok || fail "inspect: $(head -20 inspect.txt)"
"$bin" inspect routine.wpilog --motor leader | grep -q "^routine.wpilog \[dynamic-reverse\] (wpilog)" && ok ||
  fail "inspect --motor lists the tests"

# Round trip: one time per loop, so the reader's interpolation is exact.
python3 "$src/tests/support/wpilog_writer.py" same.wpilog --same-times same_ || fail "writer, same times"
"$bin" axis same.wpilog --motor leader -q -o same.yaml 2> /dev/null || fail "fit of same.wpilog"
"$bin" axis same_quasistatic-forward.csv same_quasistatic-reverse.csv same_dynamic-forward.csv same_dynamic-reverse.csv \
  --col q=position --col tau=voltage --col qd=velocity -q -o csv.yaml 2> /dev/null || fail "fit of the CSVs"
estimates() { sed -n '/^  estimates:/,/^  [a-z]/p' "$1" | grep '^    [a-z_]*: {value' | sed 's/  #.*//'; }
[ -n "$(estimates same.yaml)" ] && [ "$(estimates same.yaml)" = "$(estimates csv.yaml)" ] && ok ||
  fail "round trip differs: $(diff <(estimates same.yaml) <(estimates csv.yaml) | head -6)"

# No static friction (Ks 0): Ks is bounded, not refused, and not pinned to
# a wrong interval: [0, ...] with a warning "bounded only"; the inertia's
# interval holds its truth (a Ks held at its bound at another cutoff still
# counts in the processing's spread; before, both intervals missed).
python3 "$src/tests/support/wpilog_writer.py" ks0.wpilog --ks 0 || fail "writer, Ks 0"
"$bin" axis ks0.wpilog --motor leader -q -o ks0.yaml 2> ks0.err || fail "Ks 0: $(cat ks0.err)"
grep -q "bounded only: coulomb = " ks0.err && grep -q "^    coulomb: {value: .*ci95: \[0, " ks0.yaml && ok ||
  fail "Ks 0 bounded: $(grep coulomb ks0.yaml ks0.err | head -3)"
holds ks0.yaml inertia=0.3 viscous=2.5 coulomb=0

# An elevator (constant gravity: Kg is the offset) and an arm (Kg cos q)
# told with --test; the arm logged in Rotations as SysIdRoutine logs an
# angular mechanism (converted to Radians: the same estimates as the arm
# logged in radians, per radian), and with dynamic tests of 0.4 s, 18
# samples each, as a 7 V arm test lasts (used, not refused: they are what
# determines Ka).
python3 "$src/tests/support/wpilog_writer.py" elevator.wpilog --mechanism elevator || fail "writer, elevator"
"$bin" axis elevator.wpilog --motor leader --test elevator -q -o elevator.yaml 2> elevator.err || fail "elevator: $(cat elevator.err)"
holds elevator.yaml inertia=0.3 viscous=2.5 coulomb=0.25 offset=0.6
python3 "$src/tests/support/wpilog_writer.py" arm.wpilog --mechanism arm || fail "writer, arm"
python3 "$src/tests/support/wpilog_writer.py" arm_rot.wpilog --mechanism arm --rotations || fail "writer, arm in rotations"
"$bin" axis arm.wpilog --motor leader --test arm -q -o arm.yaml 2> arm.err || fail "arm: $(cat arm.err)"
holds arm.yaml inertia=0.3 viscous=2.5 coulomb=0.25 gravity_cos=0.6 gravity_sin=0
# What SysId users look at: with --plot, each test's measured rate beside the
# rate the fitted model simulates from the test's start under its voltage;
# the plot changes no estimate.
if command -v gnuplot > /dev/null; then
  "$bin" axis arm.wpilog --motor leader --test arm -q -o arm_plotted.yaml --plot arm.svg 2> /dev/null &&
    grep -q "rate: measured, and simulated by the fitted model" arm.svg &&
    [ "$(grep -c 'dynamic-forward\] model' arm.svg)" -ge 2 ] &&
    cmp -s <(grep -v "command:" arm.yaml) <(grep -v "command:" arm_plotted.yaml) && ok ||
    fail "the plot's simulated rates: $(grep -c 'rate: measured' arm.svg)"
else
  echo "skipped: gnuplot is not installed (the --plot check)"
fi
"$bin" axis arm_rot.wpilog --motor leader --test arm -o arm_rot.yaml > arm_rot.txt 2>&1 &&
  grep -q "logged in Rotations: converted to Radians" arm_rot.txt && ok || fail "arm in rotations: $(head -c 600 arm_rot.txt)"
holds arm_rot.yaml inertia=0.3 viscous=2.5 coulomb=0.25 gravity_cos=0.6 gravity_sin=0
python3 "$src/tests/support/wpilog_writer.py" arm_short.wpilog --mechanism arm --dynamic 0.4 || fail "writer, short arm"
"$bin" axis arm_short.wpilog --motor leader --test arm -q -o arm_short.yaml 2> arm_short.err || fail "short arm tests: $(cat arm_short.err)"
holds arm_short.yaml inertia=0.3 viscous=2.5 coulomb=0.25 gravity_cos=0.6 gravity_sin=0

# Other names: RobotPy's own logging, AdvantageKit's, no state entry.
python3 "$src/tests/support/wpilog_writer.py" robotpy.wpilog --names robotpy || fail "writer, robotpy names"
python3 "$src/tests/support/wpilog_writer.py" kit.wpilog --names advantagekit || fail "writer, AdvantageKit names"
python3 "$src/tests/support/wpilog_writer.py" nostate.wpilog --names robotpy --no-state || fail "writer, no state"
entries=(--entry voltage=/drive/appliedVoltage --entry position=/drive/leftPosition --entry velocity=/drive/leftVelocity)
expect 3 "robotpy.wpilog: a WPILib DataLog without a recognised SysId routine.*--entry voltage=NAME" -- axis robotpy.wpilog
"$bin" inspect robotpy.wpilog > robotpy_inspect.txt 2>&1 && grep -q "no SysId routine recognised.*--entry voltage=NAME" \
  robotpy_inspect.txt && grep -q "/sysid/testType .*string, 838 records" robotpy_inspect.txt && ok ||
  fail "inspect of a log without a routine: $(head -8 robotpy_inspect.txt)"
"$bin" axis robotpy.wpilog "${entries[@]}" --entry state=/sysid/testType --unit Meters -q -o robotpy.yaml 2> robotpy.err ||
  fail "fit with --entry: $(cat robotpy.err)"
[ -n "$(estimates robotpy.yaml)" ] && [ "$(estimates robotpy.yaml)" = "$(estimates fit.yaml)" ] && ok ||
  fail "--entry differs from SysIdRoutine's names: $(diff <(estimates robotpy.yaml) <(estimates fit.yaml) | head -6)"
grep -q 'Kv: {value: .*# V s/Meters' robotpy.yaml && ok || fail "--unit Meters: $(grep -A5 '^feedforward' robotpy.yaml)"
"$bin" axis kit.wpilog -q -o kit.yaml 2> kit.err || fail "AdvantageKit's naming: $(cat kit.err)"
[ "$(estimates kit.yaml)" = "$(estimates fit.yaml)" ] && grep -q "AdvantageKit's naming (state entry '/RealOutputs/Shooter/SysIdState')" kit.yaml &&
  grep -q 'Kv: {value: .*# V s/Radians' kit.yaml && ok || fail "AdvantageKit's naming: $(grep -m2 AdvantageKit kit.yaml)"
"$bin" axis nostate.wpilog "${entries[@]}" --unit Meters -q -o nostate.yaml 2> nostate.err || fail "no state: $(cat nostate.err)"
grep -q "tests found from the voltage pattern.*quasistatic-forward .*quasistatic-forward .*quasistatic-reverse .*dynamic-forward .*dynamic-reverse" nostate.yaml &&
  grep -q "test quasistatic-forward: run 2 of 2" nostate.yaml && ok || fail "tests from the voltage: $(grep -m1 'voltage pattern' nostate.yaml)"
holds nostate.yaml inertia=0.3 viscous=2.5 coulomb=0.25
expect 2 "--entry speed=x: expected ROLE=NAME, ROLE one of voltage, position, velocity, state" -- axis robotpy.wpilog --entry speed=x
expect 2 "--entry voltage=b: the voltage entry is named twice" -- axis robotpy.wpilog --entry voltage=a --entry voltage=b
expect 2 "robotpy.wpilog needs the velocity entry too" -- axis robotpy.wpilog --entry voltage=/drive/appliedVoltage \
  --entry position=/drive/leftPosition
expect 3 "robotpy.wpilog: no entry '/drive/nothing' \(--entry velocity\)" -- axis robotpy.wpilog --entry voltage=/drive/appliedVoltage \
  --entry position=/drive/leftPosition --entry velocity=/drive/nothing
expect 3 "robotpy.wpilog: entry 'struct:Pose2d' \(--entry velocity\) is of type struct:Pose2d, not a number" -- axis robotpy.wpilog \
  --entry voltage=/drive/appliedVoltage --entry position=/drive/leftPosition --entry velocity=struct:Pose2d
expect 3 "robotpy.wpilog: entry '/drive/leftPosition' \(--entry state\) is of type double, not a string" -- axis robotpy.wpilog \
  "${entries[@]}" --entry state=/drive/leftPosition
expect 2 "--entry: .*axis_steps.csv is no WPILog" -- axis "$src/data/axis_steps.csv" --entry voltage=a
# A scaled position keeps no unit of the log's.
expect 2 "--col q=21.15\*position changes the position the log declares in 'Meters': name the unit of the result with --unit" -- \
  axis routine.wpilog --motor leader --col 'q=21.15*position' --col 'qd=21.15*velocity'

# Cut inside a record: refused with the offset; cut at the header: not a log.
size=$(stat -c %s routine.wpilog)
head -c $((size - 3)) routine.wpilog > cut.wpilog
expect 3 "cut.wpilog: record at offset [0-9]+ (claims [0-9]+ bytes of payload|is cut short)" -- axis cut.wpilog --motor leader
head -c 10 routine.wpilog > header.wpilog
expect 3 "header.wpilog: not a WPILib DataLog" -- axis header.wpilog
finish
