#!/usr/bin/env bash
# ROS bags, rosbag2 SQLite3 and MCAP, ROS 1 (docs/formats.md#ros-bags), written by
# tests/support/rosbag2_writer.py (Python's sqlite3 and struct, independent of
# the reader) from data/axis_steps.csv: joint "axis" carries the CSV's samples
# (header stamps = its t), joint "wheel" beside it, receive times 3 ms later,
# messages out of order, messages without "axis", another topic.
#  - the bag's fit equals the CSV's fit to the last digit, with the same
#    sample count, for the current schema, the old one and the bag folder;
#  - refusals name what to give: several joints (--joint), an unknown
#    topic or joint (found ones listed); a cut or corrupt bag is exit 3;
#  - inspect lists the topics, the joints and the fields each carries;
#  - a bag streamed from its file reads as the same bag read whole from a pipe.
# Usage: rosbag_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
source "$src/tests/cli/cli_test_lib.sh"
if ! python3 -c 'import sqlite3' 2> /dev/null; then
  echo "python3 with sqlite3 not installed: the bag writer cannot run (skipped)"
  exit 0
fi
writer="$src/tests/support/rosbag2_writer.py"
python3 "$writer" "$src/data/axis_steps.csv" bag.db3 && python3 "$writer" "$src/data/axis_steps.csv" old.db3 --old-schema &&
  python3 "$writer" "$src/data/axis_steps.csv" folder_bag --folder || { echo "FAIL: writer"; exit 1; }

estimates() { sed -n '/^  estimates:/,/^  [a-z]/p' "$1" | grep '^    [a-z_]*: {value' | sed 's/  #.*//'; }
samples() { grep -o 'samples: [0-9]*' "$1" | head -1; }
"$bin" axis "$src/data/axis_steps.csv" -q -o csv.yaml 2> /dev/null || fail "fit of the CSV"
for bag in bag.db3 old.db3 folder_bag; do
  "$bin" axis "$bag" --joint axis -q -o bag.yaml 2> bag.err || { fail "fit of $bag: $(cat bag.err)"; continue; }
  [ -n "$(estimates csv.yaml)" ] && [ "$(estimates bag.yaml)" = "$(estimates csv.yaml)" ] &&
    [ "$(samples bag.yaml)" = "$(samples csv.yaml)" ] && ok ||
    fail "$bag differs from the CSV: $(diff <(estimates bag.yaml; samples bag.yaml) <(estimates csv.yaml; samples csv.yaml) | head -6)"
  grep -q "^warning: $bag: 8 messages without axis left out" bag.err && ok || fail "$bag: the left-out messages: $(cat bag.err)"
done
grep -q "4 messages out of time order: sorted by header stamp" bag.yaml && ok || fail "the disorder note"
"$bin" axis bag.db3 --joint axis --time receive -q -o receive.yaml 2> /dev/null &&
  grep -q "time t: the bag's receive times" receive.yaml && ok || fail "--time receive"

expect 2 "bag.db3: topic /joint_states carries 2 joints \(wheel, axis\): give --joint NAME" -- axis bag.db3
expect 2 "--joint elbow: bag.db3 /joint_states has no such joint \(found: wheel, axis\)" -- axis bag.db3 --joint elbow
expect 2 "--joint: .*axis_steps.csv is no ROS bag; --joint chooses in a bag's JointState topic" -- axis "$src/data/axis_steps.csv" --joint axis
expect 2 "--motor: bag.db3 is no WPILog" -- axis bag.db3 --joint axis --motor leader
expect 2 "--topic /tf: bag.db3 has no such JointState topic \(found: /joint_states\)" -- axis bag.db3 --topic /tf --joint axis
head -c 20000 bag.db3 > cut.db3
expect 3 "cut.db3: " -- axis cut.db3 --joint axis
{ head -c 100 bag.db3; head -c 100000 /dev/urandom; } > garbage.db3
expect 3 "garbage.db3: " -- axis garbage.db3 --joint axis

# MCAP (zstd, lz4 and uncompressed chunks, a channel inside a chunk): the same
# messages give the same fit as the db3 twin.
"$bin" axis bag.db3 --joint axis -q -o db3.yaml 2> /dev/null
for kind in zstd lz4 none; do
  python3 "$writer" "$src/data/axis_steps.csv" "bag_$kind.mcap" --mcap "$kind" || { fail "MCAP writer ($kind)"; continue; }
  "$bin" axis "bag_$kind.mcap" --joint axis -q -o mcap.yaml 2> mcap.err && [ "$(estimates mcap.yaml)" = "$(estimates db3.yaml)" ] &&
    [ "$(samples mcap.yaml)" = "$(samples db3.yaml)" ] && ok || fail "MCAP $kind differs from the db3: $(cat mcap.err)"
done
# A corrupt chunk (a byte of the compressed data changed) and cuts: exit 3
# naming the offset; never a crash or a hang (cut every 997 bytes).
python3 - bag_zstd.mcap bad_chunk.mcap << 'PY'
import sys
b = bytearray(open(sys.argv[1], "rb").read())
b[len(b) // 2] ^= 0xFF
open(sys.argv[2], "wb").write(b)
PY
expect 3 "bad_chunk.mcap: MCAP (chunk|record) at offset [0-9]+" -- axis bad_chunk.mcap --joint axis
size=$(stat -c %s bag_lz4.mcap)
cut_failures=0
for ((cut = 9; cut < size; cut += 997)); do
  head -c "$cut" bag_lz4.mcap > cut.mcap
  timeout 20 "$bin" inspect cut.mcap > /dev/null 2> cut.err
  code=$?
  { [ "$code" -eq 3 ] && grep -q "^drivetrain-fit: cut.mcap: MCAP" cut.err; } || cut_failures=$((cut_failures + 1))
done
[ "$cut_failures" -eq 0 ] && ok || fail "$cut_failures cuts of an MCAP not refused with an offset (last: $(cat cut.err))"

# ROS 1 bags (format 2.0; bz2, lz4 and uncompressed chunks; a second
# JointState topic): the same fit as the db3; --topic chosen by name.
for kind in bz2 lz4 none; do
  python3 "$writer" "$src/data/axis_steps.csv" "ros1_$kind.bag" --ros1 "$kind" || { fail "ROS 1 writer ($kind)"; continue; }
  "$bin" axis "ros1_$kind.bag" --topic /joint_states --joint axis -q -o ros1.yaml 2> ros1.err &&
    [ "$(estimates ros1.yaml)" = "$(estimates db3.yaml)" ] && [ "$(samples ros1.yaml)" = "$(samples db3.yaml)" ] && ok ||
    fail "ROS 1 $kind differs from the db3: $(cat ros1.err)"
done
expect 2 "ros1_bz2.bag: 2 JointState topics \(/joint_states, /gripper/joint_states\): give --topic" -- axis ros1_bz2.bag --joint axis
"$bin" inspect ros1_lz4.bag > inspect1.txt 2>&1 && grep -q "ROS 1 (2.0) bag, 2 topics" inspect1.txt &&
  grep -q "/gripper/joint_states: joints finger (15)" inspect1.txt && ok || fail "inspect of a ROS 1 bag: $(head -8 inspect1.txt)"
python3 - ros1_bz2.bag bad.bag << 'PY'
import sys
b = bytearray(open(sys.argv[1], "rb").read())
b[6000] ^= 0xFF  # inside the first chunk's compressed data
open(sys.argv[2], "wb").write(b)
PY
expect 3 "bad.bag: ROS bag (chunk|record) at offset [0-9]+" -- axis bad.bag --topic /joint_states --joint axis

# An elastic joint's two encoders in one topic: --joint-motor, --joint-link
# give the joint fit the CSV's columns; the same estimates as the CSV.
python3 "$writer" "$src/data/joint_example.csv" elastic.db3 --elastic || fail "elastic writer"
"$bin" joint "$src/data/joint_example.csv" --params "$src/data/joint_start.yaml" --method id -q -o joint_csv.yaml 2> /dev/null
"$bin" joint elastic.db3 --joint-motor motor --joint-link link --params "$src/data/joint_start.yaml" --method id -q \
  -o joint_bag.yaml 2> joint.err && [ -n "$(estimates joint_csv.yaml)" ] && [ "$(estimates joint_bag.yaml)" = "$(estimates joint_csv.yaml)" ] &&
  ok || fail "elastic joint from a bag: $(cat joint.err) $(diff <(estimates joint_bag.yaml) <(estimates joint_csv.yaml) | head -4)"

# A bag on a regular file is streamed (read piece by piece); one from a pipe
# is read whole and parsed in memory: both read the same.
for bag in bag.db3 bag_zstd.mcap bag_none.mcap ros1_bz2.bag ros1_none.bag; do
  "$bin" inspect "$bag" --topic /joint_states --joint axis --json > streamed.json 2>&1 &&
    cat "$bag" | "$bin" inspect /dev/stdin --topic /joint_states --joint axis --json 2>&1 | sed "s|/dev/stdin|$bag|g" > whole.json &&
    [ -s streamed.json ] && cmp -s streamed.json whole.json && ok ||
    fail "$bag streamed differs from in memory: $(diff streamed.json whole.json | head -6)"
done

"$bin" inspect bag.db3 > inspect.txt 2>&1 || fail "inspect: $(cat inspect.txt)"
grep -q "/joint_states: joints wheel (3608), axis (3600); position in 3608, velocity in 8, effort in 3608 of 3608" inspect.txt &&
  grep -q "/rosout .*rcl_interfaces/msg/Log (cdr), 6 messages" inspect.txt && ok || fail "inspect: $(head -12 inspect.txt)"
finish
