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
#  - a log cut inside a record is refused with its offset (exit 3).
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
# Every estimate's interval holds the simulated truth.
for pair in inertia=0.3 viscous=2.5 coulomb=0.25 offset=0; do
  name=${pair%=*}; truth=${pair#*=}
  line=$(grep "^    $name: {value" fit.yaml)
  low=$(sed -n 's/.*ci95: \[\([^,]*\), .*/\1/p' <<< "$line"); high=$(sed -n 's/.*ci95: \[[^,]*, \([^]]*\)\].*/\1/p' <<< "$line")
  awk -v l="$low" -v h="$high" -v t="$truth" 'BEGIN { exit !(l <= t && t <= h) }' && ok ||
    fail "$name: [$low, $high] misses $truth"
done
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

# Cut inside a record: refused with the offset; cut at the header: not a log.
size=$(stat -c %s routine.wpilog)
head -c $((size - 3)) routine.wpilog > cut.wpilog
expect 3 "cut.wpilog: record at offset [0-9]+ (claims [0-9]+ bytes of payload|is cut short)" -- axis cut.wpilog --motor leader
head -c 10 routine.wpilog > header.wpilog
expect 3 "header.wpilog: not a WPILib DataLog" -- axis header.wpilog
finish
