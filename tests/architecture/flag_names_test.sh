#!/usr/bin/env bash
# No flag spelling in lib/ (issue 25): the library names an option by its
# field between marks, ‹free›, and the tools print the flag, --free
# (apps/common/cli_support.h: ShowFlags). This test reads every string and
# character literal of lib/ (comments skipped) and fails on one that holds
# "--" before a letter, naming the file and line.
# Usage: flag_names_test.sh SOURCE_DIR
set -u
src="$1"
report=$(find "$src/lib" -name '*.cc' -o -name '*.h' | sort | xargs awk '
  FNR == 1 { in_block = 0 }
  {
    line = $0; n = length(line); i = 1; literal = ""
    while (i <= n) {
      c = substr(line, i, 1); two = substr(line, i, 2)
      if (in_block) { if (two == "*/") { in_block = 0; i += 2 } else i++; continue }
      if (two == "/*") { in_block = 1; i += 2; continue }
      if (two == "//") break
      if (c == "\"" || c == "\x27") {
        quote = c; j = i + 1; text = ""
        while (j <= n && substr(line, j, 1) != quote) {
          if (substr(line, j, 1) == "\\") { text = text substr(line, j, 2); j += 2 } else { text = text substr(line, j, 1); j++ }
        }
        literal = literal " " text
        i = j + 1
        continue
      }
      i++
    }
    checked++
    if (literal ~ /--[a-z]/) { printf "FAIL: %s:%d: a flag in a string: %s\n", FILENAME, FNR, $0; bad++ }
  }
  END { printf "%d lines checked\n%d failed\n", checked, bad + 0 }')
echo "$report"
echo "$report" | grep -q "^0 failed$"
