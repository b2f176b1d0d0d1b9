#!/usr/bin/env bash
# Every options struct of lib/ validates itself: a `struct NameOptions {`
# (or NameSettings, NameRequest)
# declares `bool IsValid(std::string* error) const` (core/option_check.h),
# which its run calls once at its entry.
set -u
bad=0
checked=0
while IFS= read -r header; do
  while IFS=: read -r line name; do
    checked=$((checked + 1))
    body=$(awk -v start="$line" 'NR >= start { print; if ($0 ~ /^};/) exit }' "$header")
    if ! grep -q "bool IsValid(std::string\* error) const" <<< "$body"; then
      echo "FAIL: ${header#$1/}:$line: $name has no IsValid"
      bad=$((bad + 1))
    fi
  done < <(grep -Eno '^struct [A-Za-z]*(Options|Settings|Request) \{' "$header" | sed 's/struct //; s/ {$//')
done < <(find "$1/lib" -name '*.h' | sort)
echo "$checked options, settings and request structs checked"
echo "$((checked - bad)) passed, $bad failed"
[ "$checked" -gt 0 ] && [ "$bad" -eq 0 ]
