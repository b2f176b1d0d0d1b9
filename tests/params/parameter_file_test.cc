#include "params/parameter_file.h"
#include "models/axis.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "core/estimate_record.h"

using namespace driveid;

namespace {
const char* kValid =
    "drivetrain:\n"
    "  n_g: 80\n"
    "  k_Tl: 15000.0\n"
    "  k_Tg: 18375\n"
    "  Theta_motor: 6.453e-5\n"
    "  Theta_g: 6.72e-6\n"
    "  d_g: 0.016\n"
    "  tau_c: 5.0\n";

std::string ErrorOf(const std::string& text) {
  try {
    ParseParameterFile("p.yaml", text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("reads the drivetrain section with units") {
  const auto file = ParseParameterFile("p.yaml", kValid);
  REQUIRE(file.Find<DriveTrainSection>());
  CHECK(file.Find<DriveTrainSection>()->gear_ratio == 80.0);
  CHECK(file.Find<DriveTrainSection>()->motor_inertia == 6.453e-5);
  CHECK(file.Find<DriveTrainSection>()->coulomb_friction == 5.0);
}

TEST_CASE("formatted files read back unchanged, with a fit section too") {
  auto file = ParseParameterFile("p.yaml", kValid);
  file.Find<DriveTrainSection>()->viscous_friction = 0.015984787675731638;  // needs all 17 digits
  FitResult fit;
  fit.estimates.push_back({"d_g", 0.015984787675731638, 2e-5, 0.01594, 0.01602});
  fit.correlation = {1.0};
  fit.channels.push_back({"a \"quoted\" log.csv:tau_link", 201, 0.1, 99.5});
  fit.singular_values = {1.0};
  fit.converged = true;
  FitProvenance provenance{"drivetrain-fit step 'a b.csv'", "0.1.0", "reduced", {{"a b.csv", "00ff", 201, "", {}}}};
  const std::string text = FormatParameterFile(file, &fit, &provenance);
  const auto again = ParseParameterFile("q.yaml", text);
  REQUIRE(again.Find<DriveTrainSection>());
  CHECK(again.Find<DriveTrainSection>()->viscous_friction == file.Find<DriveTrainSection>()->viscous_friction);
  CHECK(again.Find<DriveTrainSection>()->link_stiffness == file.Find<DriveTrainSection>()->link_stiffness);
  CHECK(again.had_fit_section);
  // Written with no fit of its own, the file keeps the fit it read, as it was.
  CHECK(FormatParameterFile(again) == text);
  auto without = again;
  without.fit_text.clear();
  CHECK(FormatParameterFile(without) == FormatParameterFile(file));
}

TEST_CASE("a fit of many parameters writes its strongest correlations, and the file reads back") {
  // 1003 parameters (1000 logs with an offset each): the matrix alone was 8 MB,
  // beyond what a parameter file may be (1 MiB).
  const std::size_t p = 1003;
  FitResult fit;
  for (std::size_t i = 0; i < p; ++i) fit.estimates.push_back({"e" + std::to_string(i), 1.0, 0.1, 0.8, 1.2});
  fit.correlation.assign(p * p, 0.0);
  for (std::size_t i = 0; i < p; ++i) {
    for (std::size_t j = 0; j < p; ++j) fit.correlation[i * p + j] = i == j ? 1.0 : 0.001 * static_cast<double>((i + j) % 7);
  }
  fit.correlation[700 * p + 2] = fit.correlation[2 * p + 700] = -0.9;  // the strongest
  fit.correlation[5 * p + 1] = fit.correlation[1 * p + 5] = 0.5;        // the second
  fit.singular_values.assign(p, 1.0);
  fit.converged = true;
  FitProvenance provenance{"drivetrain-fit step ...", "0.1.0", "reduced", {}};
  const auto file = ParseParameterFile("p.yaml", kValid);
  const std::string text = FormatParameterFile(file, &fit, &provenance);
  CHECK(text.size() < 300000);
  CHECK(text.find("  correlation:  # 1003 parameters: the 40 strongest pairs") != std::string::npos);
  const auto first = text.find("    - [e700, e2, -0.9000]"), second = text.find("    - [e5, e1, 0.5000]");
  CHECK(first != std::string::npos);
  CHECK(second != std::string::npos);
  CHECK(first < second);
  const auto strongest = StrongestCorrelations(fit, 2);
  REQUIRE(strongest.size() == 2);
  CHECK(strongest[0].first == 700);
  CHECK(strongest[0].second == 2);
  CHECK(strongest[1].correlation == 0.5);
  const auto again = ParseParameterFile("q.yaml", text);
  CHECK(again.had_fit_section);
  CHECK(again.fit_estimates.size() == p);
}

TEST_CASE("bad parameter files name file, line, column and key") {
  CHECK(ErrorOf(std::string(kValid) + "  k_TL: 3\n") ==
        "p.yaml:9:3: drivetrain.k_TL: unknown key (known: n_g, k_Tl, k_Tg, Theta_motor, Theta_g, d_g, tau_c)");
  CHECK_THAT(ErrorOf("drivetrain:\n  n_g: 80\n  k_Tl: -15000\n"),
             Catch::StartsWith("p.yaml:3:9: drivetrain.k_Tl: must be > 0, got -15000"));
  CHECK(ErrorOf("drivetrain:\n  n_g: 80\n  k_Tl: .nan\n") == "p.yaml:3:9: drivetrain.k_Tl: not a finite number: \".nan\"");
  CHECK_THAT(ErrorOf("drivetrain:\n  n_g: 80\n  k_Tl: 1e101\n"),
             Catch::StartsWith("p.yaml:3:9: drivetrain.k_Tl = 1e101: outside the range of parameter values"));
  CHECK_THAT(ErrorOf("drivetrain:\n  n_g: 80\n  k_Tl: -1e-101\n"), Catch::Contains("outside the range"));
  std::string zero = kValid;
  zero.replace(zero.find("tau_c: 5.0"), 10, "tau_c: 0");
  CHECK(ErrorOf(zero) == "no error");  // 0 is in range
  CHECK(ErrorOf("drivetrain:\n  n_g: eighty\n") == "p.yaml:2:8: drivetrain.n_g: not a finite number: \"eighty\"");
  CHECK_THAT(ErrorOf("drivetrain:\n  n_g: 80\n"), Catch::Contains("drivetrain.k_Tl: missing value"));
  CHECK_THAT(ErrorOf("drivetrain: [1, 2\n"), Catch::StartsWith("p.yaml:"));
  CHECK_THAT(ErrorOf("drivetrain: [1, 2\n"), Catch::Contains("invalid YAML"));
  CHECK(ErrorOf("") == "p.yaml: empty parameter file");
  CHECK(ErrorOf("drivetrian:\n  n_g: 80\n") ==
        "p.yaml:1:1: drivetrian: unknown section (known: drivetrain, planar_robot, axis, cdrive, joint, frf, serial_robot, robot, feedforward, feedback, fit)");
  CHECK(ErrorOf("drivetrain:\n  n_g: 80\n  n_g: 81\n") == "p.yaml:3:3: drivetrain.n_g: key appears twice");
  CHECK(ErrorOf("- 1\n- 2\n") == "p.yaml:1:1: parameter file: expected a mapping of keys");
  CHECK_THAT(ErrorOf(std::string(kValid) + "  tau_c2: [1]\n"), Catch::Contains("unknown key"));
}

TEST_CASE("cdrive section with control reads back unchanged") {
  const std::string text =
      "cdrive:\n"
      "  p: 0.06\n"
      "  I_h: 6e-4\n"
      "  I_c: 1.6e-3\n"
      "  m: 2\n"
      "  beta: 0.002655\n"
      "  gamma: 0.004333\n"
      "  delta: 0.1086\n"
      "  eta: 0.1501\n"
      "  k_t: 0.5\n"
      "  control: {K_P: 7.17, K_I: 0.0239, law: PD, dead_zone: 0.5, rate_limit: 50}\n";
  const auto file = ParseParameterFile("c.yaml", text);
  REQUIRE(file.Find<CDriveSection>());
  CHECK(file.Find<CDriveSection>()->coulomb_collar == 0.1501);
  CHECK(file.Find<CDriveSection>()->torque_constant == 0.5);
  REQUIRE(file.Find<CDriveControlSection>());
  CHECK(file.Find<CDriveControlSection>()->law == ControlLaw::kPD);
  CHECK(file.Find<CDriveControlSection>()->second_gain == 0.0239);
  const auto again = ParseParameterFile("d.yaml", FormatParameterFile(file));
  CHECK(FormatParameterFile(again) == FormatParameterFile(file));
  CHECK(again.Find<CDriveControlSection>()->law == ControlLaw::kPD);
  // Absent optional values read as "not given" and are not written.
  const auto bare = ParseParameterFile("e.yaml", "cdrive:\n  p: 0.06\n");
  CHECK_FALSE(bare.Find<CDriveSection>()->viscous_motor);
  CHECK(FormatParameterFile(bare).find("beta") == std::string::npos);
}

TEST_CASE("bad cdrive sections are named precisely") {
  CHECK(ErrorOf("cdrive:\n  p: 0.06\n  control: {K_P: 1, K_I: 0, law: PIDD}\n") ==
        "p.yaml:3:34: cdrive.control.law: must be PI, PD or PID");
  CHECK_THAT(ErrorOf("cdrive:\n  p: 0.06\n  control:\n    K_P: 1\n    K_I: 0\n    Kd: 3\n"),
             Catch::StartsWith("p.yaml:6:5: cdrive.control.Kd: unknown key"));
  CHECK_THAT(ErrorOf("cdrive:\n  p: -0.06\n"), Catch::StartsWith("p.yaml:2:6: cdrive.p: must be > 0"));
  CHECK_THAT(ErrorOf("cdrive:\n  I_h: 1\n"), Catch::Contains("cdrive.p: missing value"));
  CHECK_THAT(ErrorOf("cdrive:\n  p: 0.06\n  k_t: 0\n"), Catch::StartsWith("p.yaml:3:8: cdrive.k_t: must be > 0"));
}

TEST_CASE("deeply nested input is refused before yaml-cpp recurses into it") {
  CHECK_THAT(ErrorOf(std::string(100000, '[')), Catch::Contains("nested deeper than a parameter file can be"));
  std::string indented = "drivetrain:\n";
  for (int i = 1; i < 200; ++i) indented += std::string(static_cast<std::size_t>(i), ' ') + "a:\n";
  CHECK_THAT(ErrorOf(indented), Catch::Contains("nested deeper"));
  CHECK_THAT(ErrorOf(std::string(2 << 20, '#')), Catch::Contains("larger than"));
}

TEST_CASE("fuzzer regression: a file with only a fit section has no model to use") {
  // Found by tests/fuzz/parameter_file_fuzzer: accepted, but formatted to a
  // comment-only file that reads back as empty.
  CHECK(ErrorOf("fit:\n  command: \"x\"\n  converged: true\n") ==
        "p.yaml: no model section (drivetrain, planar_robot, axis, cdrive, joint, frf, serial_robot, robot)");
}

TEST_CASE("fuzzer regression: an axis section with every value empty reads back after formatting") {
  // Found by tests/fuzz/parameter_file_fuzzer (tests/fuzz/regressions/parameter_file_axis_all_empty.yaml).
  const auto file = ParseParameterFile("p.yaml", "axis:\n  inertia: \n  offset:\n");
  REQUIRE(file.Find<AxisSection>());
  const std::string formatted = FormatParameterFile(file);
  const auto again = ParseParameterFile("q.yaml", formatted);
  CHECK(again.Find<AxisSection>());
  CHECK(FormatParameterFile(again) == formatted);
}

TEST_CASE("fuzzer regression: a kept fit section whose flow sequence closes at column 0 reads back whole") {
  // Found by tests/fuzz/parameter_file_fuzzer (tests/fuzz/regressions/parameter_file_fit_flow_column0.yaml):
  // the fit section written back as it was read must end where the parser
  // says the next key begins, not at the first line without indentation.
  const std::string text = "axis:\n  inertia: 1\nfit:\n  correlation:\n    a: [1.0,\n \n]\n  converged: true\n";
  const auto file = ParseParameterFile("p.yaml", text);
  CHECK(file.fit_text == "fit:\n  correlation:\n    a: [1.0,\n \n]\n  converged: true\n");
  const std::string formatted = FormatParameterFile(file);
  const auto again = ParseParameterFile("q.yaml", formatted);
  CHECK(again.had_fit_section);
  CHECK(FormatParameterFile(again) == formatted);
  // A section that does not read back alone (a flow-style document) is not kept.
  CHECK(ParseParameterFile("f.yaml", "{axis: {inertia: 1}, fit: {converged: true}}").fit_text.empty());
}

TEST_CASE("fuzzer regression: the fuzzer's own check on its input (a fit section cut at a column-0 bracket)") {
  const char* source_dir = std::getenv("DRIVEID_SOURCE_DIR");
  REQUIRE(source_dir != nullptr);
  std::ifstream in(std::string(source_dir) + "/tests/fuzz/regressions/parameter_file_fit_flow_column0.yaml",
                   std::ios::binary);
  REQUIRE(in);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  try {
    const auto file = ParseParameterFile("fuzz.yaml", bytes.str());
    const std::string formatted = FormatParameterFile(file);
    const auto again = ParseParameterFile("formatted.yaml", formatted);
    CHECK(FormatParameterFile(again) == formatted);
  } catch (const InputError&) {
    SUCCEED("refused: fine");
  }
}

TEST_CASE("one YAML document only; the fit section's keys are checked") {
  CHECK_THAT(ErrorOf(std::string(kValid) + "---\naxis: {}\n"), Catch::Contains("a second YAML document"));
  CHECK_THAT(ErrorOf(std::string(kValid) + "fit:\n  converged: true\n  comand: x\n"),
             Catch::Contains("fit.comand: unknown key"));
}

TEST_CASE("a file name that is not UTF-8 is escaped in the provenance and reads back") {
  auto file = ParseParameterFile("p.yaml", kValid);
  FitResult fit;
  fit.estimates.push_back({"d_g", 0.016, 2e-5, 0.01594, 0.01602});
  fit.correlation = {1.0};
  fit.singular_values = {1.0};
  FitProvenance provenance{"drivetrain-fit step", "0.1.0", "reduced", {{"log\xff\xfe-\xc3\xa9.csv", "00ff", 3, "", {}}}};
  const std::string text = FormatParameterFile(file, &fit, &provenance);
  CHECK(text.find("log\\xff\\xfe-\xc3\xa9.csv") != std::string::npos);  // raw bytes escaped, UTF-8 kept
  CHECK(ParseParameterFile("q.yaml", text).had_fit_section);
}

TEST_CASE("the feed-forward section reads back unchanged; bad keys are named with file and line") {
  auto file = ParseParameterFile("p.yaml", "axis:\n  inertia: 0.05\n");
  file.feedforward = {kAxisFeedforwardLaw, "V", "Meters", {{"Ks", 0.0600394, 0.0123, ""}, {"Kv", 0.22421, 0.002, ""}, {"Kg_angle", -2.9, 0.1, ""}}};
  const std::string text = FormatParameterFile(file);
  const ParameterFile back = ParseParameterFile("p.yaml", text);
  REQUIRE(back.feedforward.gains.size() == 3);
  CHECK(back.feedforward.effort_unit == "V");
  CHECK(back.feedforward.position_unit == "Meters");
  CHECK(back.feedforward.gains[1].key == "Kv");
  CHECK(back.feedforward.gains[1].value == 0.22421);
  CHECK(back.feedforward.gains[1].standard_error == 0.002);
  CHECK(back.feedforward.gains[1].unit == "V s/Meters");
  CHECK(back.feedforward.gains[2].unit == "rad");
  CHECK(FormatParameterFile(back) == text);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  Kx: {value: 1}\n") ==
        "p.yaml:4:3: feedforward.Kx: unknown key (known: law, effort_unit, position_unit, mechanism, Ks, Ks_forward, Ks_backward, "
        "Kv, Kv_forward, Kv_backward, Ka, Kg, Kg_angle, offset, beta, gamma_half, delta, eta, dead_zone, rate_limit)");
  // SysId's analysis type reads back; another is refused.
  file.feedforward.mechanism = "simple";
  const std::string typed = FormatParameterFile(file);
  CHECK(typed.find("  mechanism: simple") != std::string::npos);
  CHECK(ParseParameterFile("p.yaml", typed).feedforward.mechanism == "simple");
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  mechanism: drivetrain\n") ==
        "p.yaml:4:14: feedforward.mechanism: expected simple, elevator or arm (SysId's analysis type)");
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  law: pid\n") ==
        "p.yaml:4:8: feedforward.law: \"pid\": expected axis or cdrive");
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  Ks: {std: 1}\n") == "p.yaml:4:7: feedforward.Ks: needs a value");
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  Ks: {value: nan}\n").find("p.yaml:4:15: feedforward.Ks.value") == 0);
}

TEST_CASE("units that could end a comment, start a key or an escape: neither written nor read; too long is refused") {
  auto file = ParseParameterFile("p.yaml", "axis:\n  inertia: 0.05\n");
  for (const std::string& units : {std::string("Rad\n  Kg: {value: 99, std: 0}"), std::string("Rad\r  Kg: {value: 99}"),
                                   std::string("m\" # \\ \x01"), std::string("Rad\xe2\x80\xa8Kg: 1"),
                                   std::string("\\u002a/x"), std::string("a--b"), std::string("m\xff")}) {
    INFO(units);
    file.feedforward = {kAxisFeedforwardLaw, "V", units, {{"Ks", 0.06, 0.01, ""}, {"Kv", 0.22, 0.002, ""}}};
    CHECK_THROWS_WITH(FormatParameterFile(file), Catch::StartsWith("feedforward.position_unit: not a unit name: "));
  }
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  position_unit: \"m\\n  Kg: 1\"\n")
            .find("p.yaml:4:18: feedforward.position_unit: not a unit name: a byte that is not printable ASCII") == 0);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  effort_unit: \"V*/x\"\n")
            .find("p.yaml:4:16: feedforward.effort_unit: not a unit name: \"*/\"") == 0);
  for (const char* fine : {"V", "N m", "V s/Meters", "V s^2/(rad)", "kg m^2", "%", "1/s"}) {
    file.feedforward = {kAxisFeedforwardLaw, "V", fine, {{"Ks", 0.06, 0.01, ""}}};
    CHECK(ParseParameterFile("p.yaml", FormatParameterFile(file)).feedforward.position_unit == fine);
  }
  file.feedforward.position_unit = std::string(65, 'm');
  CHECK_THROWS_AS(FormatParameterFile(file), OutputError);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  position_unit: " + std::string(65, 'm') + "\n") ==
        "p.yaml:4:18: feedforward.position_unit: 65 bytes: at most 64");
}

TEST_CASE("unknown keys are refused at every level; the writer writes only what the reader accepts") {
  CHECK(ErrorOf("axis:\n  inertia: 1\nfeedforward:\n  Ks: {value: 1, std: 0.1, foo: 3}\n") ==
        "p.yaml:4:28: feedforward.Ks.foo: unknown key (known: value, std)");
  CHECK(ErrorOf("axis:\n  inertia: 1\nfit:\n  estimates:\n    inertia: {value: 1, std: 0.1, bias: 2}\n")
            .find("fit.estimates.inertia.bias: unknown key (known: value, std, ci95)") != std::string::npos);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfit:\n  estimates:\n    inertia: 3\n")
            .find("fit.estimates.inertia: expected a mapping") != std::string::npos);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfit:\n  data:\n    - {file: a.csv, sha256: 00, samples: 3, extra: 1}\n")
            .find("fit.data.extra: unknown key") != std::string::npos);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfit:\n  derived:\n    d_g: {value: 1, std: 0.1, unit: 3}\n")
            .find("fit.derived.d_g.unit: unknown key") != std::string::npos);
  // What a fit of data scaled by 1e150 would write: refused, not written unreadable.
  auto file = ParseParameterFile("p.yaml", "axis:\n  inertia: 0.05\n");
  file.Find<AxisSection>()->inertia = 5e148;
  try {
    FormatParameterFile(file);
    FAIL("written");
  } catch (const OutputError& e) {
    CHECK(std::string(e.what()).find("axis.inertia = 5e+148: outside what a parameter file holds") == 0);
  }
  file.Find<AxisSection>()->inertia = 0.05;
  FitResult fit;
  fit.estimates.push_back({"inertia", 0.05, 1e-120, 0.05, 0.05});
  fit.correlation = {1.0};
  fit.singular_values = {1.0};
  FitProvenance provenance{"drivetrain-fit axis", "0.1.0", "", {}};
  CHECK_THROWS_AS(FormatParameterFile(file, &fit, &provenance), OutputError);
  fit.estimates[0].standard_error = 1e-4;
  fit.estimates[0].ci95_low = 0.0498;
  fit.estimates[0].ci95_high = 0.0502;
  const auto read = ParseParameterFile("q.yaml", FormatParameterFile(file, &fit, &provenance)).fit_estimates;
  REQUIRE(read.size() == 1);
  // The record (core/estimate_record.h) reads back as written: value to the
  // last bit, std and interval to six digits; the JSON has its keys.
  CHECK(read[0].value == 0.05);
  CHECK(read[0].standard_error == 1e-4);
  CHECK(read[0].ci95_low == 0.0498);
  CHECK(read[0].ci95_high == 0.0502);
  CHECK(EstimateRecordKeys() == std::vector<std::string>{"value", "std", "ci95"});
  CHECK(ErrorOf("axis:\n  inertia: 1\nfit:\n  estimates:\n    inertia: {value: 1}\n")
            .find("fit.estimates.inertia: needs a value and a std") != std::string::npos);
  CHECK(ErrorOf("axis:\n  inertia: 1\nfit:\n  estimates:\n    inertia: {value: 1, std: 0.1, ci95: [2, 1]}\n")
            .find("fit.estimates.inertia.ci95 = [2, 1]: the low end lies above the high end") != std::string::npos);
}

TEST_CASE("long provenance text is abbreviated so the file reads back; a file the reader would refuse is not written") {
  auto file = ParseParameterFile("p.yaml", kValid);
  FitResult fit;
  fit.estimates.push_back({"d_g", 0.016, 2e-5, 0.01594, 0.01602});
  fit.correlation = {1.0};
  fit.singular_values = {1.0};
  const std::string expression(200000, 'x');
  FitProvenance provenance{"drivetrain-fit axis --col tau=" + expression, "0.1.0", "", {{"log.csv", "00ff", 3, "", {"tau = " + expression}}}};
  const std::string text = FormatParameterFile(file, &fit, &provenance);
  CHECK(text.find(" bytes in all)") != std::string::npos);
  CHECK(text.size() < 10000);
  CHECK(ParseParameterFile("q.yaml", text).had_fit_section);
  provenance.data.assign(20000, {"a_long_log_file_name_of_a_big_campaign.csv", std::string(64, 'f'), 3, "", {}});
  CHECK_THROWS_WITH(FormatParameterFile(file, &fit, &provenance),
                    Catch::Contains("a parameter file holds at most 1048576; nothing written"));
}

TEST_CASE("the frf section reads back, its method text escaped, its band checked") {
  ParameterFile file;
  FrequencyResponseSection frf;
  frf.resonance_hz = 11.6;
  frf.resonance_hz_std = 0.05;
  frf.antiresonance_hz = 5.8;
  frf.antiresonance_hz_std = 0.02;
  frf.band_hz = std::array<double, 2>{0.5, 50.0};
  frf.method = "periodic\n  resonance_hz: 99 \"quoted\"";
  file.Set(frf);
  const std::string text = FormatParameterFile(file);
  const ParameterFile back = ParseParameterFile("p.yaml", text);
  const auto* read = back.Find<FrequencyResponseSection>();
  REQUIRE(read != nullptr);
  CHECK(*read->resonance_hz == 11.6);
  CHECK(*read->antiresonance_hz_std == 0.02);
  CHECK((*read->band_hz)[1] == 50.0);
  CHECK(*read->method == *frf.method);
  CHECK(FormatParameterFile(back) == text);
  CHECK(ErrorOf("frf:\n  band_hz: [5, 1]\n").find("frf.band_hz: expected 0 <= low <= high") != std::string::npos);
  CHECK(ErrorOf("frf:\n  resonance: 3\n").find("resonance") != std::string::npos);
}
