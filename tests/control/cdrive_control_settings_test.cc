// The C-drive controller's settings from `cdrive.control`
// (control/cdrive_control_settings.h): every key of the table lands in its
// own setting (each set alone to a distinct value), the rest keep their
// defaults; the two printed gains are required, the periods and limits must
// be positive, each refusal naming `cdrive.control.KEY`.
#include <string>

#include <catch2/catch.hpp>

#include "control/cdrive_control_settings.h"
#include "core/errors.h"

namespace driveid {
namespace {

CDriveControlSection Required() {
  CDriveControlSection s;
  s.proportional_gain = 7.17;
  s.second_gain = 0.0239;
  return s;
}

TEST_CASE("each key sets its own setting and no other; the law is taken when given") {
  const CDriveControlSettings defaults = MakeControlSettings(Required());
  const auto& table = CDriveControlParameterTable();
  REQUIRE(table.size() == 8);
  for (std::size_t i = 0; i < table.size(); ++i) {
    CDriveControlSection s = Required();
    s.*(table[i].in_section) = 100.0 + static_cast<double>(i);
    const CDriveControlSettings settings = MakeControlSettings(s);
    INFO(table[i].spec.key);
    for (std::size_t j = 0; j < table.size(); ++j) {
      CHECK(settings.*(table[j].in_model) == (i == j ? 100.0 + static_cast<double>(i) : defaults.*(table[j].in_model)));
    }
    CHECK(settings.law == ControlLaw::kPI);
  }
  CDriveControlSection pid = Required();
  pid.law = ControlLaw::kPID;
  CHECK(MakeControlSettings(pid).law == ControlLaw::kPID);
}

TEST_CASE("the printed gains are required; periods and limits must be positive; refusals name the key") {
  CDriveControlSection s = Required();
  s.second_gain.reset();
  CHECK_THROWS_WITH(MakeControlSettings(s), Catch::Contains("cdrive.control.K_I: missing value"));
  s = Required();
  s.proportional_gain.reset();
  CHECK_THROWS_WITH(MakeControlSettings(s), Catch::Contains("cdrive.control.K_P: missing value"));
  for (const char* key : {"rate_limit", "velocity_window", "sample_time", "encoder_counts"}) {
    s = Required();
    for (const auto& row : CDriveControlParameterTable()) {
      if (std::string(row.spec.key) == key) s.*(row.in_section) = 0.0;
    }
    INFO(key);
    CHECK_THROWS_AS(MakeControlSettings(s), InputError);
    CHECK_THROWS_WITH(MakeControlSettings(s), Catch::Contains(std::string("cdrive.control.") + key + ": must be > 0"));
  }
  s = Required();
  s.dead_zone = 0.0;  // no dead zone is a setting
  CHECK(MakeControlSettings(s).dead_zone == 0.0);
  s.dead_zone = -0.1;  // a negative one is not
  CHECK_THROWS_WITH(MakeControlSettings(s), Catch::Contains("cdrive.control.dead_zone: must be >= 0"));
}

}  // namespace
}  // namespace driveid
