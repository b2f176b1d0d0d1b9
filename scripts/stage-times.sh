# Sourced by scripts/setup, scripts/test and scripts/fuzz (not run).
# stage NAME COMMAND...: runs COMMAND; when DRIVEID_STAGE_TIMES names a file
# (.ci/run sets it), appends "NAME<TAB>SECONDS" to it, also when COMMAND
# fails. Returns COMMAND's status. scripts/ci-times prints the table.
stage() {
  local name="$1" start status=0
  shift
  start=$(date +%s.%N)
  "$@" || status=$?
  if [ -n "${DRIVEID_STAGE_TIMES:-}" ]; then
    awk -v name="$name" -v start="$start" -v end="$(date +%s.%N)" -v status="$status" \
      'BEGIN { printf "%s\t%.0f%s\n", name, end - start, status == 0 ? "" : "\t(failed)" }' >> "$DRIVEID_STAGE_TIMES"
  fi
  return "$status"
}
