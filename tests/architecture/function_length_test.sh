#!/usr/bin/env bash
# No function in lib/ or apps/ longer than 100 lines (signature to closing
# brace), so that each does one thing a reader can hold (issue 25). Braces
# are counted after comments, strings and character literals are removed; a
# function is a top-level brace block whose text since the previous ; { or }
# has a ')' and is no namespace, class, struct, enum or initialiser.
# Usage: function_length_test.sh SOURCE_DIR [LIMIT]
set -u
src="$1"
limit="${2:-100}"
report=$(find "$src/lib" "$src/apps" -name '*.cc' -o -name '*.h' | sort | xargs awk -v limit="$limit" '
  FNR == 1 { depth = 0; infn = 0; pending = ""; pending_line = 0; in_block_comment = 0 }
  {
    line = $0
    # Block comments, line comments, strings and characters out.
    if (in_block_comment) { if (sub(/.*\*\//, "", line)) in_block_comment = 0; else next }
    gsub(/\/\*[^*]*\*+([^/*][^*]*\*+)*\//, "", line)
    if (sub(/\/\*.*/, "", line)) in_block_comment = 1
    gsub(/\\./, "", line)
    gsub(/"[^"]*"/, "\"\"", line)
    gsub(/\047[^\047]*\047/, "0", line)
    sub(/\/\/.*/, "", line)
    if (line ~ /^[ \t]*#/) next
    for (i = 1; i <= length(line); ++i) {
      c = substr(line, i, 1)
      if (c == "{") {
        if (!infn && pending ~ /\)/ && pending !~ /^[ \t]*(namespace|class|struct|enum|union)([ \t]|$)/ &&
            substr(pending, 1, index(pending, "(")) !~ /=/) {
          infn = 1; fndepth = depth; start = pending_line; name = pending
        }
        ++depth; pending = ""; pending_line = 0
      } else if (c == "}") {
        --depth; pending = ""; pending_line = 0
        if (infn && depth == fndepth) {
          infn = 0
          if (FNR - start + 1 > limit) {
            gsub(/^[ \t]+|[ \t]+$/, "", name); gsub(/[ \t]+/, " ", name)
            printf "%s:%d: %d lines: %s\n", FILENAME, start, FNR - start + 1, substr(name, 1, 70)
          }
        }
      } else if (c == ";") {
        pending = ""; pending_line = 0
      } else if (c !~ /[ \t]/ || pending != "") {
        if (pending_line == 0) pending_line = FNR
        pending = pending c
      }
    }
    if (pending != "") pending = pending " "
  }')
checked=$(find "$src/lib" "$src/apps" -name '*.cc' -o -name '*.h' | wc -l)
if [ -n "$report" ]; then
  echo "FAIL: functions longer than $limit lines (split them into named steps):"
  echo "$report"
  exit 1
fi
echo "$checked files: no function longer than $limit lines"
