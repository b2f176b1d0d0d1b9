// params/feedback_section.h: a feedback section written reads back unchanged
// (values, stds, the speed loop's polynomials); unknown keys and loops are
// refused, on reading by file and position, on writing before anything is
// written.
#include "params/feedback_section.h"

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

TEST_CASE("feedback section: written, read back unchanged; unknown keys refused both ways") {
  FeedbackController c;
  c.loop = "speed";
  c.preset = "custom";
  c.effort_unit = "N m";
  c.position_unit = "rad";
  c.values = {{"kp", 0.0123456789012345, 1e-4, 0.0121, 0.01265}, {"ki", 0.5, 0.01}, {"period", 0.001, 0.0},
              {"notch_hz", 8.1, 0.0}};
  c.numerator = {1.0, 2.5, 3.25};
  c.denominator = {1.0, 0.5, 0.0};
  const std::string text = FormatFeedbackSection(c);
  const FeedbackController back = ParseFeedbackSection("f.yaml", YAML::Load(text)["feedback"]);
  CHECK(back.loop == c.loop);
  CHECK(back.preset == c.preset);
  CHECK(back.effort_unit == c.effort_unit);
  REQUIRE(back.values.size() == c.values.size());
  for (std::size_t i = 0; i < c.values.size(); ++i) {
    CHECK(back.values[i].key == c.values[i].key);
    CHECK(back.values[i].value == c.values[i].value);
    CHECK(back.values[i].standard_error == Approx(c.values[i].standard_error));
    CHECK(back.values[i].HasInterval() == c.values[i].HasInterval());
    if (c.values[i].HasInterval()) {
      CHECK(back.values[i].ci95_low == c.values[i].ci95_low);
      CHECK(back.values[i].ci95_high == c.values[i].ci95_high);
    }
  }
  CHECK(back.numerator == c.numerator);
  CHECK(back.denominator == c.denominator);
  CHECK(FormatFeedbackSection(back) == text);

  const YAML::Node unknown = YAML::Load("feedback:\n  loop: velocity\n  kq: 1\n")["feedback"];
  CHECK_THROWS_WITH(ParseFeedbackSection("f.yaml", unknown), Catch::Contains("f.yaml") && Catch::Contains("kq"));
  FeedbackController bad = c;
  bad.loop = "torque";
  CHECK_THROWS_AS(FormatFeedbackSection(bad), OutputError);
}

TEST_CASE("feedback section: a gain's interval that does not hold its value, or is no pair, is refused where it stands") {
  const auto parse = [](const std::string& gain) {
    return ParseFeedbackSection("f.yaml", YAML::Load("feedback:\n  loop: velocity\n  kp: " + gain + "\n")["feedback"]);
  };
  CHECK(parse("{value: 2, std: 0.1, ci95: [1.8, 2.3]}").values.front().ci95_high == 2.3);
  CHECK_THROWS_WITH(parse("{value: 2, std: 0.1, ci95: [2.1, 2.3]}"),
                    Catch::Contains("f.yaml:3:") && Catch::Contains("feedback.kp.ci95: [2.1, 2.3] does not hold the value 2"));
  CHECK_THROWS_WITH(parse("{value: 2, std: 0.1, ci95: [1.8]}"), Catch::Contains("feedback.kp.ci95: expected [low, high]"));
  CHECK_THROWS_WITH(parse("{value: 2, std: 0.1, ci95: [1.8, nan]}"), Catch::Contains("feedback.kp.ci95"));
}

TEST_CASE("feedback section: a negative std or a period not above 0 is refused where it stands") {
  const YAML::Node negative = YAML::Load("feedback:\n  loop: velocity\n  kp: {value: 1, std: -0.1}\n")["feedback"];
  CHECK_THROWS_WITH(ParseFeedbackSection("f.yaml", negative), Catch::Contains("f.yaml:3") && Catch::Contains("feedback.kp.std = -0.1"));
  const YAML::Node period = YAML::Load("feedback:\n  loop: velocity\n  kp: 1\n  period: -0.02\n")["feedback"];
  CHECK_THROWS_WITH(ParseFeedbackSection("f.yaml", period), Catch::Contains("feedback.period = -0.02"));
  // The C-drive, speed and other loops keep their polynomials and margins: only these two rules here.
  const YAML::Node fine = YAML::Load("feedback:\n  loop: velocity\n  kp: {value: 1, std: 0}\n  period: 0.02\n")["feedback"];
  CHECK_NOTHROW(ParseFeedbackSection("f.yaml", fine));
}
