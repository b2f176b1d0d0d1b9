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
  [system]="core system"
  [logs]="core models signal system logs"
  [robot_description]="core models system robot_description"
  [params]="core models control system robot_description params"
  [sim]="core models control signal system logs sim"
  [design]="core models design"
  [fit]="core models signal system logs sim fit"
  [report]="core models control system logs params robot_description signal sim fit design report"
  [export]="core models control system logs params robot_description signal report export"
  [workflow]="core models control signal system logs robot_description params sim fit design report export workflow"
)
bad=0
checked=0
for layer in "${!allowed[@]}"; do
  while IFS= read -r file; do
    while IFS=: read -r line target; do
      checked=$((checked + 1))
      dir="${target%%/*}"
      case " ${allowed[$layer]} " in
        *" $dir "*) ;;
        *) echo "FAIL: ${file#"$1"/}:$line includes \"$target\" (layer '$dir' is not below '$layer')"; bad=$((bad + 1)) ;;
      esac
    done < <(grep -no '^#include "[a-z_]*/[^"]*"' "$file" | sed 's/#include "//; s/"$//')
  done < <(find "$lib/$layer" -type f \( -name '*.h' -o -name '*.cc' \))
done
# Every layer directory must be declared here (a new one must be placed).
for dir in "$lib"/*/; do
  name=$(basename "$dir")
  [ -n "${allowed[$name]+x}" ] || { echo "FAIL: lib/$name is not a known layer"; bad=$((bad + 1)); }
done
# Inside every layer no include runs back up: a file's includes (its
# header's and its source's together) form no cycle with another file's.
for layer in "${!allowed[@]}"; do
  edges=$(find "$lib/$layer" -type f \( -name '*.h' -o -name '*.cc' \) | while read -r file; do
            rel=${file#"$lib/"}
            unit=${rel%.*}
            grep -o "^#include \"$layer/[a-z_/0-9]*" "$file" | sed 's|^#include "||' | while read -r target; do
              [ "$target" != "$unit" ] && echo "$unit $target"
            done
          done | sort -u)
  checked=$((checked + 1))
  if ! cycle=$(printf '%s\n' "$edges" | tsort 2>&1 >/dev/null) || [ -n "$cycle" ]; then
    echo "FAIL: lib/$layer: its files include each other in a cycle: $(echo "$cycle" | tr '\n' ' ')"
    bad=$((bad + 1))
  fi
done
# The rooms inside a layer: a file of a folder below includes only the
# folders listed for it (a format reads through the table, never the table
# through a format; a model's fit stands on fit/core and on the fits listed).
# Every folder of these layers must be listed.
declare -A rooms=(
  [logs]="logs"
  [logs/formats]="logs logs/formats"
  [fit]=""
  [fit/core]="fit/core"
  [fit/axis]="fit/core fit/axis"
  [fit/joint]="fit/core fit/axis fit/joint"
  [fit/step]="fit/core fit/step"
  [fit/frf]="fit/core fit/frf"
  [fit/cdrive]="fit/core fit/cdrive"
  [fit/robot]="fit/core fit/robot"
  [fit/validation]="fit/core fit/axis fit/cdrive fit/step fit/validation"
)
for layer in logs fit; do
  while IFS= read -r dir; do
    room=${dir#"$lib/"}
    checked=$((checked + 1))
    if [ -z "${rooms[$room]+x}" ]; then
      echo "FAIL: lib/$room is not a known room of lib/$layer (list it in tests/architecture/layering_test.sh)"
      bad=$((bad + 1))
      continue
    fi
    for file in "$dir"/*.h "$dir"/*.cc; do
      [ -f "$file" ] || continue
      while IFS=: read -r line target; do
        checked=$((checked + 1))
        case " ${rooms[$room]} " in
          *" ${target%/*} "*) ;;
          *) echo "FAIL: lib/$room/$(basename "$file"):$line includes \"$target\" (lib/${target%/*} is not open to lib/$room)"
             bad=$((bad + 1)) ;;
        esac
      done < <(grep -no "^#include \"$layer/[^\"]*\"" "$file" | sed 's/#include "//; s/"$//')
    done
  done < <(find "$lib/$layer" -type d)
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
