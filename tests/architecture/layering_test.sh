#!/usr/bin/env bash
# The library's layers (lib/CMakeLists.txt): no file includes a header of a
# layer it does not depend on. The build enforces this too (a layer sees
# only the headers it links); this test names the offending line.
set -u
lib="$1/lib"
declare -A allowed=(
  [core]="core"
  [models]="core models"
  [signal]="core signal"
  [control]="core models control"
  [io]="core models control signal io"
  [sim]="core models control signal io sim"
  [design]="core models design"
  [fit]="core models signal io sim fit"
  [report]="core models control io signal sim fit design report"
  [export]="core models control io signal report export"
  [workflow]="core models control io signal sim fit design report export workflow"
)
bad=0
checked=0
for layer in "${!allowed[@]}"; do
  for file in "$lib/$layer"/*; do
    while IFS=: read -r line target; do
      checked=$((checked + 1))
      dir="${target%%/*}"
      case " ${allowed[$layer]} " in
        *" $dir "*) ;;
        *) echo "FAIL: lib/$layer/$(basename "$file"):$line includes \"$target\" (layer '$dir' is not below '$layer')"; bad=$((bad + 1)) ;;
      esac
    done < <(grep -no '^#include "[a-z_]*/[^"]*"' "$file" | sed 's/#include "//; s/"$//')
  done
done
# Every layer directory must be declared here (a new one must be placed).
for dir in "$lib"/*/; do
  name=$(basename "$dir")
  [ -n "${allowed[$name]+x}" ] || { echo "FAIL: lib/$name is not a known layer"; bad=$((bad + 1)); }
done
# Inside the top layers no include runs back up: a file's includes (its
# header's and its source's together) form no cycle with another file's.
for layer in report export workflow; do
  edges=$(for file in "$lib/$layer"/*; do
            unit=$(basename "${file%.*}")
            grep -o "^#include \"$layer/[a-z_]*" "$file" | sed "s|.*/||" | while read -r target; do
              [ "$target" != "$unit" ] && echo "$unit $target"
            done
          done | sort -u)
  checked=$((checked + 1))
  if ! cycle=$(printf '%s\n' "$edges" | tsort 2>&1 >/dev/null) || [ -n "$cycle" ]; then
    echo "FAIL: lib/$layer: its files include each other in a cycle: $(echo "$cycle" | tr '\n' ' ')"
    bad=$((bad + 1))
  fi
done
# The tests mirror the library: every layer has its folder of tests.
for dir in "$lib"/*/; do
  name=$(basename "$dir")
  checked=$((checked + 1))
  ls "$1/tests/$name"/*_test.cc > /dev/null 2>&1 || { echo "FAIL: tests/$name holds no test of lib/$name"; bad=$((bad + 1)); }
done
# The tools call the workflow: no file of apps/ includes a fit/ or sim/ header.
while IFS=: read -r file line target; do
  echo "FAIL: $file:$line includes \"$target\" (apps/ calls workflow/, not fit/ or sim/)"
  bad=$((bad + 1))
done < <(cd "$1" && grep -rno '^#include "\(fit\|sim\)/[^"]*"' apps | sed 's/#include "//; s/"$//')
checked=$((checked + 1))
echo "$checked includes checked"
echo "$((checked - bad)) passed, $bad failed"
[ "$bad" -eq 0 ]
