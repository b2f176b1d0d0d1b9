#!/usr/bin/env bash
# Helpers shared by the CLI test scripts. Set `bin` (the executable) and
# `program` (its name in messages) before sourcing.
passed=0
failed=0
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
ok() { passed=$((passed + 1)); }

# expect CODE PATTERN -- ARGS...: exit code, a single stderr line starting
# with the program name and matching PATTERN, and no out.yaml written
# (passed as `-o out.yaml`, or with the option in EXPECT_OUTPUT, e.g. --trace).
expect() {
  local code="$1" pattern="$2"
  shift 3
  rm -f out.yaml
  "$bin" "$@" "${EXPECT_OUTPUT:--o}" out.yaml > stdout.txt 2> stderr.txt
  local got=$?
  local lines
  lines=$(wc -l < stderr.txt)
  if [ "$got" -ne "$code" ]; then
    fail "$* -> exit $got, expected $code: $(head -c 300 stderr.txt)"
  elif [ "$lines" -ne 1 ]; then
    fail "$* -> $lines stderr lines: $(head -c 300 stderr.txt)"
  elif ! grep -q "^$program: " stderr.txt; then
    fail "$* -> message does not start with the program name: $(cat stderr.txt)"
  elif grep -q "‹\|›" stderr.txt stdout.txt; then
    fail "$* -> the library's option mark reached the user (apps/common/cli_support.h: ShowFlags): $(cat stderr.txt)"
  elif ! grep -qE -- "$pattern" stderr.txt; then
    fail "$* -> message does not match /$pattern/: $(cat stderr.txt)"
  elif [ -e out.yaml ] || ls out.yaml.tmp.* > /dev/null 2>&1; then
    fail "$* -> an output file was written on failure"
  else
    ok
  fi
}

# sanitized: true when $bin was built with AddressSanitizer, whose shadow
# memory cannot be reserved under a `ulimit -v` cap (gcc links the runtime
# as libasan.so, clang into the tool itself, which then exports __asan_init).
sanitized() {
  ldd "$bin" 2> /dev/null | grep -q libasan || nm -D "$bin" 2> /dev/null | grep -q " __asan_init$"
}

finish() {
  # Nothing the tests made (outputs, messages kept in files) shows the
  # library's option marks instead of the flags.
  local marked
  marked=$(grep -rlI "‹\|›" . 2> /dev/null | head -3)
  [ -z "$marked" ] || fail "the library's option mark (‹field›) reached the user in: $marked"
  echo "$passed passed, $failed failed"
  [ "$failed" -eq 0 ]
}
