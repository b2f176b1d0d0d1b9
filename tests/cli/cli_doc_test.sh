#!/usr/bin/env bash
# docs/cli.md is the tools' --help: regenerated from BIN_DIR and compared;
# the man pages built next to the tools have one section per subcommand of it.
# Usage: cli_doc_test.sh BIN_DIR SRC
set -u
bin_dir="$1"
src="$2"
if ! diff -u "$src/docs/cli.md" <("$src/scripts/make-cli-doc" "$bin_dir"); then
  echo "FAIL: docs/cli.md differs from the tools' --help; regenerate it: scripts/make-cli-doc $bin_dir > docs/cli.md"
  exit 1
fi
echo "docs/cli.md matches --help"
for tool in drivetrain-fit cdrive-fit; do
  page="$bin_dir/$tool.1"
  if [ ! -f "$page" ]; then echo "FAIL: no man page $page (target man_pages)"; exit 1; fi
  expected=$(sed -n "s/^###* \`\($tool [a-z ]*\)\`\$/\1/p" "$src/docs/cli.md")
  actual=$(sed -n 's/^\.SS "\(.*\)"$/\1/p' "$page")
  if [ "$expected" != "$actual" ]; then
    echo "FAIL: sections of $page differ from docs/cli.md:"
    diff <(printf '%s\n' "$expected") <(printf '%s\n' "$actual")
    exit 1
  fi
  if ! grep -q '^\.TH ' "$page"; then echo "FAIL: $page has no .TH header"; exit 1; fi
  echo "$page: $(printf '%s\n' "$actual" | wc -l) subcommand sections"
done
