#!/usr/bin/env bash
# Atomic outputs and determinism (issue 5): a kill during output leaves the
# previous file intact, and every fit gives byte-identical files on a rerun.
# Usage: robustness_test.sh DRIVETRAIN_FIT CDRIVE_FIT SRC
set -u
dt="$1"
cd_bin="$2"
src="$3"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
ok() { passed=$((passed + 1)); }

# Kill during output: a large simulated log is written over an existing
# file; SIGKILL at several moments must leave the old file or the complete
# new one, never a partial file.
"$dt" simulate step --params "$src/data/paper000.yaml" --duration 0.05 -o big.csv || fail "first write"
cp big.csv old.csv
# The complete new file, made by the identical command (its command line is in the file).
mkdir reference
(cd reference && "$dt" simulate step --params "$src/data/paper000.yaml" --rate 200000 --duration 20 -o big.csv) \
  || fail "reference write"
mv reference/big.csv complete.csv
interrupted=0
for delay in 0.05 0.2 0.5 1.0 1.5 2.0 2.5; do
  "$dt" simulate step --params "$src/data/paper000.yaml" --rate 200000 --duration 20 -o big.csv &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  if cmp -s big.csv old.csv || cmp -s big.csv complete.csv; then ok; else fail "partial file after a kill at ${delay}s"; fi
  # A temporary file left behind means the kill hit the write itself.
  if ls big.csv.tmp.* > /dev/null 2>&1; then
    cmp -s big.csv old.csv && interrupted=$((interrupted + 1))
    rm -f big.csv.tmp.*
  fi
  cp old.csv big.csv
done
# Deterministic variant: wait until the temporary file exists, i.e. the
# write is under way, and kill then.
for attempt in 1 2 3; do
  "$dt" simulate step --params "$src/data/paper000.yaml" --rate 200000 --duration 20 -o big.csv &
  pid=$!
  while kill -0 "$pid" 2> /dev/null && ! ls big.csv.tmp.* > /dev/null 2>&1; do sleep 0.001; done
  kill -9 "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  if ls big.csv.tmp.* > /dev/null 2>&1; then
    cmp -s big.csv old.csv && interrupted=$((interrupted + 1)) || fail "write killed midway changed the old file"
    rm -f big.csv.tmp.*
  fi
  cp old.csv big.csv
done
[ "$interrupted" -gt 0 ] && ok || fail "no kill landed during a write: the test proved nothing"

# SIGINT, SIGTERM, SIGHUP (issue 9 item 3): while an output is being written,
# the tool dies of the signal (status 128 + n), its temporary file is gone and
# the old file is unchanged. Job control puts background jobs in their own
# process group, where SIGINT is not ignored.
set -m
for signal in INT TERM HUP; do
  "$dt" simulate step --params "$src/data/paper000.yaml" --rate 200000 --duration 20 -o big.csv &
  pid=$!
  while kill -0 "$pid" 2> /dev/null && ! ls big.csv.tmp.* > /dev/null 2>&1; do sleep 0.001; done
  ls big.csv.tmp.* > /dev/null 2>&1 || fail "SIG$signal: no temporary file was seen (the test proved nothing)"
  kill -s "$signal" "$pid"
  wait "$pid"
  code=$?
  expected=$((128 + $(kill -l "$signal")))
  [ "$code" -eq "$expected" ] && ok || fail "SIG$signal: exit status $code, expected $expected"
  ls big.csv.tmp.* > /dev/null 2>&1 && fail "SIG$signal left $(ls big.csv.tmp.*)" || ok
  cmp -s big.csv old.csv && ok || fail "SIG$signal changed the old file"
  rm -f big.csv.tmp.*
done
# During a plot: a stand-in gnuplot that hangs; the signal stops it, and
# nothing is left in TMPDIR — gnuplot's script, messages and image have no
# name (SIGKILL included, which no handler sees).
mkdir -p fakebin plot_tmp
printf '#!/bin/sh\n[ -r "$1" ] || exit 9\nexec sleep 60\n' > fakebin/gnuplot
chmod +x fakebin/gnuplot
"$dt" simulate step --params "$src/data/paper000.yaml" --noise 0.1 -o plotted.csv
for signal in INT TERM HUP KILL; do
  PATH="$work/fakebin:$PATH" TMPDIR="$work/plot_tmp" "$dt" step plotted.csv --params "$src/data/paper000_start.yaml" -q \
    -o plotted.yaml --plot plotted.png &
  pid=$!
  while kill -0 "$pid" 2> /dev/null && ! pgrep -P "$pid" sleep > /dev/null 2>&1; do sleep 0.01; done
  sleeper=$(pgrep -P "$pid" sleep)
  [ -n "$sleeper" ] || fail "SIG$signal: the stand-in gnuplot did not start (the test proved nothing)"
  kill -s "$signal" "$pid"
  wait "$pid"
  code=$?
  [ "$code" -eq $((128 + $(kill -l "$signal"))) ] && ok || fail "SIG$signal during a plot: exit status $code"
  [ -z "$(ls -A plot_tmp)" ] && ok || fail "SIG$signal during a plot left $(ls -A plot_tmp)"
  if [ "$signal" = KILL ]; then
    [ -z "$sleeper" ] || kill "$sleeper" 2> /dev/null
  else
    { [ -z "$sleeper" ] || ! kill -0 "$sleeper" 2> /dev/null; } && ok || fail "SIG$signal: gnuplot still runs"
  fi
  [ ! -e plotted.yaml ] && [ ! -e plotted.png ] && ok || fail "SIG$signal during a plot wrote outputs"
done
# A temporary folder that does not exist: the plot is made all the same.
TMPDIR=/nonexistent/driveid "$dt" step plotted.csv --params "$src/data/paper000_start.yaml" -q -o plotted.yaml \
  --plot plotted.png > /dev/null 2> plot_err.txt && [ -s plotted.png ] && ok \
  || fail "TMPDIR=/nonexistent with --plot: $(cat plot_err.txt)"
rm -f plotted.yaml plotted.png
set +m

# Byte-identical reruns of every fitting subcommand (same command line).
rerun() {
  local name="$1"
  shift
  "$@" > /dev/null 2>&1 && cp "$name" "$name.first" && "$@" > /dev/null 2>&1 && cmp -s "$name" "$name.first" \
    && ok || fail "rerun of $* differs or fails"
}
"$dt" simulate step --params "$src/data/paper000.yaml" --noise 0.1 -o step.csv
rerun step.yaml "$dt" step step.csv --params "$src/data/paper000_start.yaml" -q -o step.yaml --trace step_trace.csv
"$dt" simulate axis --params "$src/data/axis_example.yaml" --noise 0.05 -o axis.csv
rerun axis.yaml "$dt" axis axis.csv --params "$src/data/axis_example.yaml" -q -o axis.yaml
rerun robot.yaml "$dt" robot "$src/data/robot_triangle.csv" --params "$src/data/robot_start.yaml" -q -o robot.yaml
rerun friction.yaml "$cd_bin" friction "$src/data/cdrive_slow_translation.csv" "$src/data/cdrive_slow_rotation.csv" \
  "$src/data/cdrive_slow_helical.csv" --params "$src/data/cdrive_start.yaml" -q -o friction.yaml
rerun inertia.yaml "$cd_bin" inertia "$src/data/cdrive_fast_translation.csv" "$src/data/cdrive_fast_rotation.csv" \
  "$src/data/cdrive_fast_helical.csv" --params "$src/data/cdrive_table1.yaml" -q -o inertia.yaml
rerun sim.csv "$cd_bin" simulate --program helical --params "$src/data/cdrive_table1.yaml" --noise 0.01 -o sim.csv

# Output names up to the file system's limit (255 bytes) are written: the
# staging name beside them is cut to fit (issue 55: 245-255 were refused).
for length in 245 250 255; do
  long_name=$(head -c $((length - 5)) /dev/zero | tr '\0' n).yaml
  "$dt" axis axis.csv --params "$src/data/axis_example.yaml" -q -o "$long_name" 2> long_err.txt &&
    [ -s "$long_name" ] && [ -z "$(ls | grep '\.tmp\.')" ] && ok || fail "a $length-byte output name: $(cat long_err.txt)"
  rm -f "$long_name"
done

# Terminal escape sequences in a file name or a key read from a file are
# shown as \x1b, never sent raw to the terminal (issue 55).
escaped=$'esc\e[31mred.csv'
cp axis.csv "$escaped"
"$dt" axis "$escaped" --from 1e9 > escape_out.txt 2> escape_err.txt
grep -q 'esc\\x1b\[31mred.csv' escape_err.txt && ! grep -q $'\e' escape_err.txt escape_out.txt && ok ||
  fail "escape in a file name reached the terminal: $(cat -v escape_err.txt)"
"$dt" axis "$escaped" --params "$src/data/axis_example.yaml" -q -o escaped.yaml &&
  sed 's/^    inertia: {value/    "in\\x1b[2Jertia": {value/' escaped.yaml > escaped_key.yaml &&
  "$dt" report escaped_key.yaml > escape_out.txt 2> escape_err.txt
! grep -q $'\e' escape_err.txt escape_out.txt && ok || fail "escape in a key reached the terminal: $(cat -v escape_out.txt escape_err.txt | head -5)"
rm -f "$escaped"

# Standard output closed by its reader (`| head`, SIGPIPE): the run dies of
# the signal (141) and, as with a full disk, changes no file and leaves no
# staging file (issue 55).
mkdir closed_pipe
closed_pipe() {
  (cd closed_pipe && { "$@" 2> /dev/null; echo $? > ../pipe_code; } | true)
  [ "$(cat pipe_code)" = 141 ] && [ -z "$(ls -A closed_pipe)" ] && ok ||
    fail "stdout closed: $* exit $(cat pipe_code), left $(ls -A closed_pipe)"
  rm -rf closed_pipe/*
}
closed_pipe "$dt" step ../step.csv --params "$src/data/paper000_start.yaml" -o p.yaml
closed_pipe "$dt" axis ../axis.csv --params "$src/data/axis_example.yaml" -o p.yaml
closed_pipe "$dt" robot "$src/data/robot_triangle.csv" --params "$src/data/robot_start.yaml" -o p.yaml
closed_pipe "$dt" validate "$src/data/paper000.yaml" ../step.csv --trace p.csv
closed_pipe "$cd_bin" friction "$src/data/cdrive_slow_translation.csv" "$src/data/cdrive_slow_rotation.csv" \
  "$src/data/cdrive_slow_helical.csv" --params "$src/data/cdrive_start.yaml" -o p.yaml
closed_pipe "$cd_bin" simulate --program helical --params "$src/data/cdrive_table1.yaml" --noise 0.01 -o p.csv
closed_pipe "$cd_bin" validate "$src/data/cdrive_table1.yaml" "$src/data/cdrive_fast_helical.csv" --trace p.csv

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
