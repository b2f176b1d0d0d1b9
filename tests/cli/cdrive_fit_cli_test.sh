#!/usr/bin/env bash
# CLI tests of cdrive-fit: bad C-drive logs and parameter files (exit 3),
# refusals (exit 4) with no output file, simulate -> friction round trip,
# reruns, report. Usage: cdrive_fit_cli_test.sh BIN SRC
set -u
bin="$1"
src="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
program=cdrive-fit
# shellcheck source=tests/cli/cli_test_lib.sh
source "$src/tests/cli/cli_test_lib.sh"

cp "$src/data/cdrive_table1.yaml" table1.yaml
for prog in translation rotation helical; do
  "$bin" simulate --program "$prog" --params table1.yaml --stroke 2 --cycles 2 --noise 0.01 -o "$prog.csv" \
    > /dev/null || fail "simulate $prog"
done

# Bad C-drive logs: exit 3 with file:line: column.
printf 't,psi_L,psi_R,tau_L\n0,0,0,0\n' > missing.csv
printf 't,psi_L,psi_R,tau_L,tau_R\n0,0,0,0,0\n0.001,0,x,0,0\n' > not_number.csv
printf 't,psi_L,psi_R,tau_L,tau_R\n0,0,0,0,0\n0.001,0,0,inf,0\n' > inf.csv
printf 't,psi_L,psi_R,i_L,i_R\n0,0,0,0,0\n0.001,0,0,1,1\n' > currents.csv
printf 't,psi_L,psi_R,i_L,tau_R\n0,0,0,0,0\n' > mixed.csv
printf 't,psi_L,psi_R,tau_L,tau_R\n0,0,0,0,0\n0,0,0,0,0\n' > time.csv
expect 3 "missing.csv:1: missing column 'tau_R' or 'i_R'" -- friction missing.csv --params table1.yaml
expect 2 "'psi_L' and 'psi_R' would both read column 'psi_L'" -- friction translation.csv --params table1.yaml --col psi_R=psi_L
expect 2 "--free: 'beta,' holds an empty parameter name" -- friction translation.csv --params table1.yaml --free beta,
expect 2 "--stroke 1e-09 with --cycles 1 at cdrive.control.sample_time .* gives 1 samples: the fit of such a log needs at least 5" -- \
  simulate --program helical --params table1.yaml --stroke 1e-9
for bad in 0 nan; do expect 2 "--window.*must be a finite number > 0" -- friction translation.csv --params table1.yaml --window "$bad"; done
for bad in -1 nan; do expect 2 "--settle.*must be a finite number >= 0" -- friction translation.csv --params table1.yaml --settle "$bad"; done
expect 3 "not_number.csv:3: column 'psi_R': not a number" -- friction not_number.csv --params table1.yaml
expect 3 "inf.csv:3: column 'tau_L': not a finite number" -- friction inf.csv --params table1.yaml
expect 3 "currents.csv: the log has currents i_L, i_R: cdrive.k_t must be given" -- friction currents.csv --params table1.yaml
expect 3 "mixed.csv: give both motor torques" -- friction mixed.csv --params table1.yaml
expect 3 "time.csv:3: column 't': time not strictly increasing" -- inertia time.csv --params table1.yaml

# Bad parameter files.
sed 's/  eta: 0.1501/  eta: -0.1501/' table1.yaml > negative.yaml
sed 's/    law: PD/    law: P/' table1.yaml > law.yaml
sed '/  beta:/d' table1.yaml > no_beta.yaml
expect 3 "negative.yaml:[0-9]+:8: cdrive.eta: must be >= 0" -- friction translation.csv --params negative.yaml
expect 3 "law.yaml:[0-9]+:10: cdrive.control.law: must be PI, PD or PID" -- friction translation.csv --params law.yaml
expect 3 "cdrive.beta is needed" -- inertia translation.csv --params no_beta.yaml
# Every missing value in one message, each with the line to add.
sed -e '/  beta:/d' -e '/  gamma:/d' -e '/  delta:/d' table1.yaml > no_friction.yaml
expect 3 "cdrive.beta, cdrive.gamma and cdrive.delta are needed \\(fixed in this fit\\)" -- inertia translation.csv --params no_friction.yaml
expect 3 "add to the cdrive section .*: 'beta: <value>' \\(.*\\[N m s/rad\\]\\), 'gamma: <value>'" -- inertia translation.csv --params no_friction.yaml
expect 3 "no 'cdrive' section" -- friction translation.csv --params "$src/data/paper000.yaml"

# Refusals: exit 4, naming what cannot be determined; no output file.
expect 4 "not identifiable.*gamma, eta.*pure rotation" -- friction rotation.csv --params table1.yaml
expect 4 "not identifiable.*I_h, I_c, m.*fix one of I_h, I_c, m" -- inertia translation.csv rotation.csv helical.csv \
  --params table1.yaml --free I_h,I_c,m
expect 4 "no usable samples" -- friction translation.csv --params table1.yaml --min-rate 1000
expect 4 "not identifiable.*beta, gamma, delta, eta.*pure translation .* fixes only beta \+ gamma" -- \
  friction translation.csv --params table1.yaml

# Usage errors: exit 2.
expect 2 "not a parameter of the friction fit" -- friction translation.csv --params table1.yaml --free beta,zeta
expect 2 "" -- simulate --program spiral --params table1.yaml
expect 2 "--stroke = -1: violated constraint" -- simulate --program rotation --params table1.yaml --stroke -1

# simulate -> friction round trip; the output reads back; reruns are identical.
if "$bin" friction translation.csv rotation.csv helical.csv --params table1.yaml -q -o fitted.yaml --trace trace.csv; then
  ok
else
  fail "friction fit of simulated logs"
fi
for key in beta gamma delta eta; do
  truth=$(awk -v k="  $key:" 'index($0, k) == 1 {print $2; exit}' table1.yaml)
  value=$(awk -v k="  $key:" 'index($0, k) == 1 {print $2; exit}' fitted.yaml)
  awk -v v="$value" -v t="$truth" 'BEGIN { d = v / t - 1; exit !(d < 0.03 && d > -0.03) }' && ok \
    || fail "$key = $value, simulated with $truth (more than 3 % off)"
done
cp fitted.yaml first.yaml
"$bin" friction translation.csv rotation.csv helical.csv --params table1.yaml -q -o fitted.yaml --trace trace.csv \
  && cmp -s fitted.yaml first.yaml && ok || fail "rerun differs"
"$bin" report fitted.yaml > report.txt && grep -q "beta = 0.00" report.txt && grep -q "+-" report.txt && ok \
  || fail "report lacks the fitted table with uncertainties"
# The eq. (31) compensation block (docs/models.md#c-drive): gamma_half is
# gamma / 2 with half its std; the controller's dead zone and rate limit.
gamma=$(awk '/^    gamma: \{value/ { gsub(/[{},]/, " "); print $3, $5 }' fitted.yaml)
half=$(awk '/^  gamma_half: \{value/ { gsub(/[{},]/, " "); print $3, $5 }' fitted.yaml)
awk -v g="$gamma" -v h="$half" 'BEGIN { split(g, a, " "); split(h, b, " ")
  exit !(a[1] > 0 && (b[1] / a[1] - 0.5)^2 < 1e-10 && (b[2] / a[2] - 0.5)^2 < 1e-6) }' \
  && grep -q "^  law: cdrive" fitted.yaml && grep -q "^  dead_zone: {value: 0.5, std: 0}  # rad/s" fitted.yaml \
  && grep -q "^  gamma_half .* N m s/rad" report.txt && ok || fail "compensation block: gamma '$gamma', half '$half'"
"$bin" friction translation.csv rotation.csv helical.csv --params fitted.yaml -q -o refit.yaml && ok \
  || fail "fit output is not a valid --params input"
for sub in friction inertia simulate report; do
  "$bin" "$sub" --help | grep -q "Example:" && ok || fail "$sub --help lacks an example"
done
# validate (docs/models.md#validation): the true parameters predict both
# motors of the simulated logs; wrong ones fit worse; refusals.
"$bin" validate table1.yaml helical.csv translation.csv --json > validate.json || fail "validate"
[ "$(grep -o '"fit_percent":[0-9.]*' validate.json | wc -l)" -eq 4 ] \
  && grep -o '"fit_percent":[-0-9.]*' validate.json | awk -F: '$2 < 90 { bad = 1 } END { exit bad }' && ok \
  || fail "validate fit %: $(cat validate.json)"
sed 's/^\(  beta: \).*/\10.5/' table1.yaml > wrong.yaml
"$bin" validate wrong.yaml helical.csv --json | grep -o '"fit_percent":[-0-9.]*' | awk -F: '$2 > 90 { bad = 1 } END { exit bad }' \
  && ok || fail "validate with a wrong beta"
printf 'axis:\n  inertia: 1\n' > no_cdrive.yaml
EXPECT_OUTPUT=--trace expect 4 "helical.csv:tau_L: no usable samples to compare" -- validate table1.yaml helical.csv --min-rate 1e300
EXPECT_OUTPUT=--trace expect 3 "no_cdrive.yaml: no 'cdrive' section" -- validate no_cdrive.yaml helical.csv
EXPECT_OUTPUT=--trace expect 3 "missing.csv:1: missing column 'tau_R' or 'i_R'" -- validate table1.yaml missing.csv

# export (docs/export.md#c-drive): the compensation law (31) as a C header
# (compiled; beta printed equals the file's) and JSON; other targets have no
# form for it.
"$bin" friction "$src"/data/cdrive_slow_*.csv --params "$src/data/cdrive_start.yaml" -q -o comp.yaml ||
  fail "friction fit for export"
beta=$(awk '/^  beta: {value:/ { gsub(/[{},]/, " "); print $3 }' comp.yaml)
"$bin" export comp.yaml --to c-header --joint ct -o comp.h &&
  printf '#include <stdio.h>\n#include "comp.h"\nint main(void) { printf("%%.17g\\n", CT_beta + 0 * CT_eta_STD); return 0; }\n' > comp_use.c &&
  cc -std=c99 -Wall -Werror comp_use.c -o comp_use && [ "$(./comp_use)" = "$(printf '%.17g' "$beta")" ] && ok ||
  fail "C-drive C header: $(./comp_use 2>&1) vs beta $beta"
"$bin" export comp.yaml --to json > comp.json && grep -q '"law":"cdrive"' comp.json && grep -q '"gamma_half":{"value":' comp.json &&
  ok || fail "C-drive JSON: $(cat comp.json)"
expect 2 "--to: mjcf not in" -- export comp.yaml --to mjcf

finish
