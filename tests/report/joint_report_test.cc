// What `report` derives from an elastic joint (report/joint_report.h),
// against the eigenvalues of the two-mass state matrix computed here:
// the resonance is the oscillating pair's |lambda| (undamped), its damping
// ratio -Re(lambda)/|lambda|, the anti-resonance the link alone on the
// spring; and the measured frequency response's values passed through.
#include <cmath>
#include <complex>
#include <string>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "params/parameter_file.h"
#include "models/frequency_response.h"
#include "report/joint_report.h"

namespace driveid {
namespace {

TEST_CASE("resonance, anti-resonance, damping ratio from the state matrix; inertia ratio and total") {
  const double jm = 0.02, jl = 0.05, k = 20.0, d = 0.05;
  const ParameterFile file = ParseParameterFile(
      "joint.yaml", "joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n  link_inertia: 0.05\n  stiffness: 20\n"
                    "  damping: 0.05\nfrf:\n  resonance_hz: 8.1\n  resonance_hz_std: 0.05\n");
  const Json report = JointReportJson(file);
  const Json& derived = report["joint"]["derived"];
  // x = (theta_m, theta_m', theta_l, theta_l'), the spring and its damper between them, nothing else.
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a(0, 1) = 1.0;
  a(1, 0) = -k / jm, a(1, 1) = -d / jm, a(1, 2) = k / jm, a(1, 3) = d / jm;
  a(2, 3) = 1.0;
  a(3, 0) = k / jl, a(3, 1) = d / jl, a(3, 2) = -k / jl, a(3, 3) = -d / jl;
  const Eigen::Vector4cd damped = a.eigenvalues();
  Eigen::Matrix4d undamped_a = a;
  undamped_a(1, 1) = undamped_a(1, 3) = undamped_a(3, 1) = undamped_a(3, 3) = 0.0;
  const Eigen::Vector4cd undamped = undamped_a.eigenvalues();
  double w_r = 0.0, zeta = 0.0;
  for (int i = 0; i < 4; ++i) {
    w_r = std::max(w_r, std::abs(undamped(i)));
    if (std::abs(damped(i).imag()) > 1e-6) zeta = -damped(i).real() / std::abs(damped(i));
  }
  CHECK(derived["resonance_hz"].get<double>() == Approx(w_r / (2.0 * M_PI)).epsilon(1e-9));
  CHECK(derived["damping_ratio"].get<double>() == Approx(zeta).epsilon(1e-9));
  // The motor-side anti-resonance: the link's own mode with the motor held.
  CHECK(derived["antiresonance_hz"].get<double>() == Approx(std::sqrt(-undamped_a(3, 2)) / (2.0 * M_PI)).epsilon(1e-12));
  CHECK(derived["inertia_ratio"].get<double>() == Approx(jl / jm));
  CHECK(derived["total_inertia"].get<double>() == Approx(jm + jl));
  CHECK(report["frf"]["resonance_hz"]["value"] == 8.1);
  CHECK(report["frf"]["resonance_hz"]["std"] == 0.05);
  const std::string text = FormatJointReport(file);
  CHECK(text.find("elastic joint") != std::string::npos);
  CHECK(text.find("8.1") != std::string::npos);
}

TEST_CASE("nothing is derived without both inertias and a stiffness; no sections, no report") {
  const ParameterFile partial =
      ParseParameterFile("joint.yaml", "joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n  stiffness: 20\n");
  CHECK_FALSE(JointReportJson(partial)["joint"].contains("derived"));
  const ParameterFile none = ParseParameterFile("axis.yaml", "axis:\n  inertia: 0.5\n");
  CHECK(FormatJointReport(none).empty());
  CHECK(JointReportJson(none).empty());
}

TEST_CASE("the frf section's table: each key read into its own member") {
  const auto& table = FrequencyResponseTable();
  REQUIRE(table.size() == 4);
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string text = std::string("frf:\n  ") + table[i].spec.key + ": " + std::to_string(i + 1) + ".5\n";
    const ParameterFile file = ParseParameterFile("frf.yaml", text);
    const FrequencyResponseSection* f = file.Find<FrequencyResponseSection>();
    REQUIRE(f != nullptr);
    INFO(table[i].spec.key);
    for (std::size_t j = 0; j < table.size(); ++j) {
      const std::optional<double>& value = f->*(table[j].in_section);
      CHECK(value.has_value() == (i == j));
      if (i == j) CHECK(*value == static_cast<double>(i + 1) + 0.5);
    }
  }
}

}  // namespace
}  // namespace driveid
