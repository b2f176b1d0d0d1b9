#!/usr/bin/env bash
# joint --method auto and oe through the command line (docs/models.md#joint-output-error):
# a stiff joint (resonance 26 Hz near the inverse-dynamics cutoff 25 Hz) in a
# PI speed loop, no link Coulomb friction: auto takes output error, which
# finds k within 2 %; the trace, the plot, multiple and single shooting.
# Release suite only (label "heavy": two minutes under the sanitizers; the
# output-error fit's code runs there in joint_oe_fit_test).
# Usage: joint_oe_cli_test.sh DRIVETRAIN_FIT SOURCE_DIR
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=cli_test_lib.sh
. "$src/tests/cli/cli_test_lib.sh"

printf 'joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n  link_inertia: 0.05\n  stiffness: 400\n  damping: 0.2\n  motor_viscous: 0.1\n  motor_coulomb: 0.2\n  link_viscous: 0.05\n  link_coulomb: 0\n  offset: 0.05\n' > stiff_truth.yaml
printf 'joint:\n  gear_ratio: 50\n' > stiff_start.yaml
"$bin" simulate joint --params stiff_truth.yaml --kp 0.0004 --ki 0.002 --duration 10 --band 1,60 --amplitude 0.5 \
  --noise 0.5 -o stiff.csv && ok || fail "simulate joint (stiff)"
"$bin" joint stiff.csv --params stiff_start.yaml --max-seconds 600 -o stiff_fit.yaml --trace stiff_trace.csv --plot stiff_fit.svg > stiff.txt 2>&1 \
  && grep -q "^method: output error (auto: the inverse-dynamics cutoff 25 Hz is below 4 x the resonance" stiff.txt \
  && grep -q "^  stiffness: \(39[2-9]\|40[0-8]\)" stiff_fit.yaml && grep -q "output error (exact ZOH" stiff_fit.yaml \
  && head -2 stiff_trace.csv | grep -q "^log,t,q_motor_measured,q_motor_model,q_link_measured,q_link_model" \
  && [ -s stiff_fit.svg ] && ok || fail "joint auto -> output error: $(cat stiff.txt)"
grep -q "^note: output error by multiple shooting: [0-9]* segments of" stiff.txt && ok \
  || fail "joint auto -> output error names its segments: $(cat stiff.txt)"
"$bin" joint stiff.csv --params stiff_start.yaml --method oe --segment none --max-seconds 600 -o /dev/null > stiff_single.txt 2>&1 \
  && grep -q "^note: output error by single shooting" stiff_single.txt && ok \
  || fail "joint --segment none: $(cat stiff_single.txt)"
finish
