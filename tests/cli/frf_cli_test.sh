#!/usr/bin/env bash
# drivetrain-fit frf end to end (docs/models.md#frequency-response): a
# two-mass joint driven open loop by a periodic multisine, generated here in
# awk (semi-implicit Euler, 20 sub-steps, torque held per sample, speed with
# sensor noise; independent of the library), its
# resonance and anti-resonance found, outputs written all or nothing, the
# parameter file read back, refusals by name.
# Usage: frf_cli_test.sh DRIVETRAIN_FIT SOURCE_DIR
set -u
bin="$1"
src="$2"
program=drivetrain-fit
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

# Link side J_m 0.5, J_l 1.5, k 2000, d 2, b_m 6, gear 10 (log in motor units):
# anti-resonance sqrt(k/J_l)/2pi = 5.8115 Hz, resonance sqrt(k (1/J_m + 1/J_l))/2pi = 11.623 Hz.
awk 'BEGIN {
  n = 10; jm = 0.5; jl = 1.5; k = 2000; d = 2; bm = 6; rate = 1000; period = 2000; ns = 20;
  h = 1 / (rate * ns); pi = atan2(0, -1); srand(7);
  print "t,tau,q_motor,qd_motor,q_link";
  for (i = 0; i < 16 * period; ++i) {
    u = 0; p = i % period;
    for (l = 1; l <= 60; ++l) u += 0.05 * cos(2 * pi * l * p / period - pi * l * (l - 1) / 60);
    noise = 0.02 * (rand() + rand() + rand() - 1.5);  # speed-sensor noise, about 2 % of the speed
    printf "%.6f,%.9g,%.9g,%.9g,%.9g\n", i / rate, u, n * xm, n * vm + noise, xl;
    for (s = 0; s < ns; ++s) {
      f = k * (xm - xl) + d * (vm - vl);
      vm += h * (n * u - f - bm * vm) / jm; vl += h * f / jl;
      xm += h * vm; xl += h * vl;
    }
  }
}' > twomass.csv

printf 'joint:\n  gear_ratio: 10\n' > gear.yaml
"$bin" frf twomass.csv --params gear.yaml --fit two-mass -o fit.yaml --csv frf.csv --plot bode.svg \
  > summary.txt 2>&1 || fail "frf fit: $(cat summary.txt)"
grep -q "^  resonance_hz: 11\.[56]" fit.yaml && ok || fail "resonance: $(grep resonance fit.yaml)"
grep -q "^  antiresonance_hz: 5\.[78]" fit.yaml && ok || fail "anti-resonance: $(grep antiresonance fit.yaml)"
grep -q "^  stiffness: 19[6-9][0-9]\|^  stiffness: 20[0-3][0-9]" fit.yaml && ok || fail "stiffness: $(grep stiffness fit.yaml)"
grep -q "method: \"periodic" fit.yaml && ok || fail "periodic method not used: $(grep method fit.yaml)"
head -2 frf.csv | tail -1 | grep -q "^frequency_hz,magnitude,phase_deg,coherence,magnitude_std,phase_std_deg,model_magnitude,model_phase_deg$" \
  && ok || fail "CSV header: $(head -2 frf.csv)"
[ -s bode.svg ] && ok || fail "no Bode plot"
# --trace, as the other commands spell it, writes the same CSV as --csv.
"$bin" frf twomass.csv --params gear.yaml --fit two-mass -q --trace frf_trace.csv && cmp -s frf.csv frf_trace.csv \
  && ok || fail "--trace and --csv differ"
# The written file reads back (as --params of another fit).
"$bin" frf twomass.csv --params fit.yaml -q -o refit.yaml && grep -q "^frf:" refit.yaml && ok || fail "fit.yaml does not read back"
# --json: one object with the fitted resonance.
"$bin" frf twomass.csv --params gear.yaml --fit two-mass --json -o /dev/null > out.json 2> err.txt \
  && grep -q '"fitted":{"resonance":{"value_hz":11\.' out.json && ok || fail "json: $(head -c 300 out.json) $(cat err.txt)"
# A response measured elsewhere (--measured): the CSV just written, read back
# in dB and with its own column names, fitted the same way.
awk -F, 'NR <= 2 { next } { printf "%s,%.9g,%s\n", $1, 20 * log($2) / log(10), $3 }' frf.csv > bode_db.csv
sed -i '1i f_hz,mag_db,phase_deg' bode_db.csv
"$bin" frf --measured bode_db.csv --col frequency=f_hz --col magnitude=mag_db --col phase=phase_deg --magnitude-unit db \
  --output-is rate --params gear.yaml --fit two-mass -o measured.yaml > measured.txt 2>&1 \
  && grep -q "^  resonance_hz: 11\.[56]" measured.yaml && grep -q "measured elsewhere" measured.yaml && ok \
  || fail "--measured: $(cat measured.txt) $(grep resonance measured.yaml)"
# A measured Bode table of the motor mobility (analytic, gear 1: J_m 0.5,
# J_l 1.5, k 2000, d 2; 1 % magnitude and 0.5 degree noise), alone and times
# a second mode (anti-resonance 35 Hz, resonance 35.5 Hz, 2 % damping) the
# two-mass model lacks: the first fits without a model warning, the second
# is named for the waves its residuals make across frequency.
bode() {
  awk -v fz="$1" -v fp="$2" 'BEGIN {
    jm = 0.5; jl = 1.5; k = 2000; d = 2; z = 0.02; pi = atan2(0, -1); srand(5);
    print "f_hz,magnitude,phase_deg";
    for (f = 1; f <= 40; f += 0.25) {
      w = 2 * pi * f; nr = k - jl * w * w; ni = d * w;
      p = (jm + jl) * k - jm * jl * w * w; q = (jm + jl) * d * w; dr = -w * q; di = w * p;
      gr = (nr * dr + ni * di) / (dr * dr + di * di); gi = (ni * dr - nr * di) / (dr * dr + di * di);
      if (fz > 0) {
        ar = 1 - (f / fz) ^ 2; ai = 2 * z * f / fz; br = 1 - (f / fp) ^ 2; bi = 2 * z * f / fp;
        hr = (ar * br + ai * bi) / (br * br + bi * bi); hi = (ai * br - ar * bi) / (br * br + bi * bi);
        t = gr * hr - gi * hi; gi = gr * hi + gi * hr; gr = t;
      }
      printf "%.4f,%.9g,%.6f\n", f, sqrt(gr * gr + gi * gi) * (1 + 0.01 * (rand() - 0.5)), atan2(gi, gr) * 180 / pi + 0.5 * (rand() - 0.5);
    }
  }'
}
printf 'joint:\n  gear_ratio: 1\n' > gear1.yaml
bode 0 0 > bode_plain.csv
bode 35 35.5 > bode_mode.csv
for table in plain mode; do
  "$bin" frf --measured "bode_$table.csv" --col frequency=f_hz --col phase=phase_deg --output-is rate --params gear1.yaml \
    --fit two-mass --free motor_inertia,link_inertia,stiffness,damping -o "bode_$table.yaml" > "bode_$table.txt" 2>&1 ||
    fail "Bode table $table: $(cat "bode_$table.txt")"
done
! grep -q "^warning: model" bode_plain.txt && awk '/^  stiffness:/ { exit !($2 > 1995 && $2 < 2005) }' bode_plain.yaml && ok ||
  fail "two-mass Bode table: $(grep -E 'warning|^stiffness' bode_plain.txt)"
grep -q "^warning: model: motor phase: fitted 8[0-9].[0-9] % (below 90 %) with residuals in long waves across frequency" \
  bode_mode.txt && ok || fail "second mode not named: $(grep warning bode_mode.txt)"
# Nothing measured is not a measurement (issue 36: exit 0 with an empty frf section).
expect 2 "--band 600,700: at or above the logs' Nyquist frequency 500 Hz" -- frf twomass.csv --params gear.yaml --band 600,700
expect 4 "no frequency response to read: 1 usable bin \(at least 5\) in --band 5,5" -- \
  frf twomass.csv --params gear.yaml --band 5,5.0000001
awk -F, 'NR == 1 { print; next } { print $1 "," $2 ",0,0," $5 }' twomass.csv > zero_output.csv
expect 4 "no frequency response to read: 0 usable bins" -- frf zero_output.csv --params gear.yaml --method welch
expect 2 "--resolution 0.1 Hz: the excitation repeats every 2 s" -- frf twomass.csv --params gear.yaml --resolution 0.1
# A measured table: coherence beyond 1 refused; the frequency column named as such.
awk -F, 'NR == 1 { print $0 ",coh"; next } { print $0 "," (NR == 2 ? 5 : 1) }' bode_db.csv > bode_coh.csv
expect 3 "measured response, bin 1 \([0-9.]+ Hz\): coherence 5: a coherence lies in 0 .. 1" -- \
  frf --measured bode_coh.csv --col frequency=f_hz --col magnitude=mag_db --col phase=phase_deg --col coherence=coh \
  --magnitude-unit db --output-is rate --params gear.yaml
# A coherence column weighs the bins (std of ln|H| and phase ~ sqrt(1 - g^2)/g):
# a table whose bins above 60 Hz are barely coherent (0.3) and noisy fits
# k closer and tighter with it than without, and the note says so. A
# preamble of two lines is skipped with --skip-rows.
awk 'BEGIN { pi = atan2(0, -1); srand(9); n = 10; jm = 0.5; jl = 1.5; k = 2000; d = 2; bm = 6;
  print "Drive XY export, axis 1"; print "units: Hz, abs, deg"; print "frequency,magnitude,phase,coherence";
  for (i = 0; i < 300; ++i) { f = exp(log(200) * i / 299); w = 2 * pi * f;
    alr = k - jl * w * w; ali = d * w; amr = k - jm * w * w; ami = (d + bm) * w;
    denr = amr * alr - ami * ali - (k * k - d * d * w * w); deni = amr * ali + ami * alr - 2 * k * d * w;
    numr = -n * n * w * ali; numi = n * n * w * alr;
    hr = (numr * denr + numi * deni) / (denr * denr + deni * deni); hi = (numi * denr - numr * deni) / (denr * denr + deni * deni);
    c = f > 60 ? 0.3 : 0.995; s = sqrt((1 - c) / c);
    g1 = sqrt(-2 * log(1 - rand())) * cos(2 * pi * rand()); g2 = sqrt(-2 * log(1 - rand())) * cos(2 * pi * rand());
    printf "%.6f,%.9g,%.6f,%g\n", f, sqrt(hr * hr + hi * hi) * exp(0.3 * s * g1), atan2(hi, hr) * 180 / pi + 0.3 * s * g2 * 180 / pi, c } }' > coherent.csv
cut -d, -f1-3 coherent.csv > incoherent.csv
for with in coherence none; do
  table=coherent.csv
  [ "$with" = none ] && table=incoherent.csv
  "$bin" frf --measured "$table" --skip-rows 2 --output-is rate --params gear.yaml --fit two-mass \
    --band 1,200 -o "coh_$with.yaml" > "coh_$with.txt" 2>&1 || fail "coherence $with: $(tail -3 "coh_$with.txt")"
done
grep -q "the measured coherence weighs the bins" coh_coherence.txt && ok || fail "coherence note: $(grep note coh_coherence.txt)"
kw=$(awk '/^stiffness / { print $2, $3 }' coh_coherence.txt) kn=$(awk '/^stiffness / { print $2, $3 }' coh_none.txt)
awk -v w="$kw" -v n="$kn" 'BEGIN { split(w, a, " "); split(n, b, " "); z = (a[1] - 2000) / a[2];
  exit !(z > -3 && z < 3 && a[2] < 0.7 * b[2]) }' && ok || fail "coherence weighting: k $kw with, $kn without"
awk -F, 'NR == 3 { print; print; next } { print }' bode_db.csv > bode_dup.csv
expect 3 "bode_dup.csv:4: column 'frequency': not strictly increasing" -- \
  frf --measured bode_dup.csv --col frequency=f_hz --col magnitude=mag_db --col phase=phase_deg --magnitude-unit db \
  --output-is rate --params gear.yaml
expect 2 "give logs, or --measured FILE" -- frf twomass.csv --measured bode_db.csv
# The same table stored one signal per row (--transpose), names first; a
# ragged row is refused naming its line.
awk -F, '{ for (j = 1; j <= NF; ++j) row[j] = row[j] (NR > 1 ? ";" : "") $j } END { for (j = 1; j <= 3; ++j) print row[j] }' \
  bode_db.csv > bode_rows.csv
"$bin" frf --measured bode_rows.csv --transpose --col frequency=f_hz --col magnitude=mag_db --col phase=phase_deg \
  --magnitude-unit db --output-is rate --params gear.yaml --fit two-mass -o measured_rows.yaml > measured_rows.txt 2>&1 \
  && grep -q "^  stiffness:" measured_rows.yaml && [ "$(grep -A3 '^  stiffness:' measured_rows.yaml)" = "$(grep -A3 '^  stiffness:' measured.yaml)" ] && ok \
  || fail "--transpose: $(cat measured_rows.txt)"
sed '2s/;[^;]*$//' bode_rows.csv > bode_ragged.csv
expect 3 "bode_ragged.csv:2: --transpose: [0-9]+ cells, line 1 has [0-9]+" -- frf --measured bode_ragged.csv --transpose \
  --col frequency=f_hz --col magnitude=mag_db --col phase=phase_deg --output-is rate --params gear.yaml
expect 2 "--transpose applies to --measured" -- frf twomass.csv --transpose
expect 2 "--output-is" -- frf --measured bode_db.csv --col frequency=f_hz --col magnitude=mag_db --col phase=phase_deg
# simulate joint plans a measurement: the shipped joint's truth (resonance
# sqrt(20 (1/0.02 + 1/0.05))/2pi = 5.955 Hz, anti-resonance sqrt(20/0.05)/2pi
# = 3.183 Hz; Coulomb friction is not in the linear model), a PI speed loop
# with the excitation injected; frf with the reference finds both within 2 %.
"$bin" simulate joint --params "$src/data/joint_example_truth.yaml" --kp 0.0004 --ki 0.002 --noise 0.5 --band 0.5,20 \
  -o sim.csv 2> sim_err.txt && head -4 sim.csv | grep -q "^t,tau,q_motor,qd_motor,q_link,r$" && ok || fail "simulate joint: $(cat sim_err.txt)"
"$bin" frf sim.csv --reference r --params "$src/data/joint_example_truth.yaml" --fit two-mass -q -o sim_fit.yaml \
  2> sim_fit.txt || fail "frf of simulate joint: $(cat sim_fit.txt)"
awk '/^  resonance_hz:/ { exit !($2 > 5.84 && $2 < 6.07) }' sim_fit.yaml && ok || fail "$(grep resonance_hz: sim_fit.yaml)"
awk '/^  antiresonance_hz:/ { exit !($2 > 3.12 && $2 < 3.25) }' sim_fit.yaml && ok || fail "$(grep antiresonance_hz: sim_fit.yaml)"
for excitation in chirp prbs; do
  "$bin" simulate joint --params "$src/data/joint_example_truth.yaml" --excitation "$excitation" --duration 8 \
    --period 8 --band 0.5,20 -o "sim_$excitation.csv" && [ "$(wc -l < "sim_$excitation.csv")" -eq 8004 ] && ok \
    || fail "simulate joint --excitation $excitation"
done
EXPECT_OUTPUT=-o expect 2 "period" -- simulate joint --params "$src/data/joint_example_truth.yaml" --period 100 --duration 10
EXPECT_OUTPUT=-o expect 3 "no 'joint' section" -- simulate joint --params "$src/data/axis_example.yaml"

# Refusals: the band below the resonance (exit 4, named), an output whose
# quantity is unknown (exit 2), an unknown free name (exit 2), a missing column (exit 3).
expect 4 "resonance" -- frf twomass.csv --params gear.yaml --fit two-mass --band 1,8
expect 2 "--output-is" -- frf twomass.csv --output tau
# No resonance inside the excited band (a band below it): a warning, exit 4
# under --strict with nothing written; exit 0 without it.
"$bin" frf twomass.csv --band 1,8 -q -o band.yaml 2> band.txt && grep -q "no resonance peak inside" band.txt && ok \
  || fail "no resonance in the band: $(cat band.txt)"
EXPECT_OUTPUT=-o expect 4 "--strict: 1 adequacy warning; nothing written: no resonance peak inside" -- frf twomass.csv \
  --band 1,8 --strict
expect 2 "'bogus' cannot be estimated" -- frf twomass.csv --fit two-mass --free bogus,stiffness
expect 3 "missing column" -- frf twomass.csv --reference r
expect 2 "averages" -- frf twomass.csv --method welch --resolution 0.05
expect 2 "finer than the shortest log" -- frf twomass.csv --method welch --resolution 1e-300
expect 2 "longer than half the longest log" -- frf twomass.csv --period 1e300
# One sample per period (found by the options fuzzer: it crashed the FFT).
expect 2 "a period needs at least 4" -- frf twomass.csv --period 0.001
expect 3 "joint.motor_inertia and joint.link_inertia are needed" -- frf twomass.csv --params gear.yaml --fit two-mass \
  --free stiffness
finish
