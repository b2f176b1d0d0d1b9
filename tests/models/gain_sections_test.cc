// The feed-forward and feedback sections' declarations (models/feedforward.h,
// models/feedback.h): unit names sorted into length and angle without
// overlap, the unit text every export target can carry, each gain's unit,
// and the feedback keys found by name with their section's units.
#include <string>

#include <catch2/catch.hpp>

#include "models/feedback.h"
#include "models/feedforward.h"

namespace driveid {
namespace {

TEST_CASE("position units: length or angle, never both; unknown names neither") {
  for (const char* unit : {"m", "mm", "Meters", "Feet", "ft", "Inches", "in"}) {
    CHECK(IsLengthUnit(unit));
    CHECK_FALSE(IsAngleUnit(unit));
  }
  for (const char* unit : {"rad", "Radians", "Rotations", "rot", "rev", "turns", "deg", "Degrees"}) {
    CHECK(IsAngleUnit(unit));
    CHECK_FALSE(IsLengthUnit(unit));
  }
  for (const char* unit : {"", "M", "meter ", "furlongs", "Rad"}) {
    CHECK_FALSE(IsLengthUnit(unit));
    CHECK_FALSE(IsAngleUnit(unit));
  }
}

TEST_CASE("unit text: every printable ASCII character sorted; nothing that closes a comment or starts an escape") {
  const std::string allowed = " /^*._()%+-";
  for (int c = 0; c < 256; ++c) {
    const std::string unit = std::string("N") + static_cast<char>(c);
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    const bool ok = alnum || (c != 0 && allowed.find(static_cast<char>(c)) != std::string::npos);
    INFO("byte " << c);
    CHECK(UnitTextProblem(unit).empty() == ok);
  }
  CHECK(UnitTextProblem("N\\u002a") == "the character '\\'");
  CHECK(UnitTextProblem("N \x01") == "a byte that is not printable ASCII");
  CHECK(UnitTextProblem("V s/m") == "");
  CHECK(UnitTextProblem("kg m^2 (rotor)") == "");
  CHECK(UnitTextProblem("a--b") == "\"--\"");
  CHECK(UnitTextProblem("a/*b") == "\"/*\"");
  CHECK(UnitTextProblem("a*/b") == "\"*/\"");
  CHECK(UnitTextProblem(std::string(64, 'x')) == "");
  CHECK(UnitTextProblem(std::string(65, 'x')) == "longer than 64 bytes");
}

TEST_CASE("each feed-forward gain's unit follows from u = Ks sgn v + Kv v + Ka a + Kg cos(q - angle) + offset") {
  for (const char* key : kFeedforwardKeys) {
    const std::string unit = FeedforwardUnit(key, "V", "Meters");
    const std::string k = key;
    INFO(k);
    if (k.rfind("Kv", 0) == 0 || k == "beta" || k == "gamma_half") {
      CHECK(unit == "V s/Meters");  // times a rate
    } else if (k == "Ka") {
      CHECK(unit == "V s^2/Meters");  // times an acceleration
    } else if (k == "Kg_angle") {
      CHECK(unit == "rad");
    } else if (k == "dead_zone") {
      CHECK(unit == "Meters/s");  // a rate
    } else if (k == "rate_limit") {
      CHECK(unit == "1/s");
    } else {
      CHECK(unit == "V");  // Ks*, Kg, offset, delta, eta: an effort
    }
  }
}

TEST_CASE("feedback keys: each found by its name, in its section's units") {
  FeedbackController f;
  f.effort_unit = "V";
  f.position_unit = "rad";
  for (const auto& k : kFeedbackKeys) {
    REQUIRE(FindFeedbackKey(k.key) == &k);
    const std::string unit = FeedbackKeyUnit(k, f);
    const std::string declared = k.unit;
    CHECK(unit == (declared == "position" ? "rad" : declared == "position/s" ? "rad/s" : declared == "effort" ? "V" : declared));
  }
  CHECK(FindFeedbackKey("Kp") == nullptr);
  CHECK(FindFeedbackKey("") == nullptr);
  f.values = {{"kp", 2.0, 0.1}, {"kd", 0.5, 0.0}};
  REQUIRE(f.Find("kd") != nullptr);
  CHECK(f.Find("kd")->value == 0.5);
  CHECK(f.Find("ki") == nullptr);
  CHECK(f.empty());
  f.loop = kFeedbackLoops[0];
  CHECK_FALSE(f.empty());
}

}  // namespace
}  // namespace driveid
