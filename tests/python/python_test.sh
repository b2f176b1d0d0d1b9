#!/usr/bin/env bash
# The Python module (docs/python.md): its pytest suite (tests/python) against
# the command line, then `cmake --install` into a fresh prefix and the
# module imported from that prefix's dist-packages alone.
# Usage: python_test.sh BIN_DIR BUILD_DIR SRC
# Exit 77 (skipped) when Debian's python3-pytest is not installed.
set -u
bin="$1"
build="$2"
src="$3"
python=/usr/bin/python3
if ! "$python" -c 'import pytest, numpy, yaml' 2> /dev/null; then
  echo "SKIP: /usr/bin/python3 has no pytest, numpy or yaml (scripts/setup installs python3-pytest, python3-numpy, python3-yaml)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
DRIVEID_BIN="$bin" DRIVEID_SRC="$src" PYTHONPATH="$build/python" \
  "$python" -m pytest -q -p no:cacheprovider "$src/tests/python" || exit 1
# Installed: the package in the prefix's Debian layout, found there alone.
cmake --install "$build" --prefix "$work/prefix" > install.log 2>&1 || { cat install.log; exit 1; }
site="$work/prefix/lib/python3/dist-packages"
found=$(PYTHONPATH="$site" "$python" -c 'import driveid; print(driveid.__file__)') || exit 1
case "$found" in
  "$site"/driveid/__init__.py) echo "ok: installed module $found" ;;
  *) echo "FAIL: the installed module was not imported from $site: $found"; exit 1 ;;
esac
