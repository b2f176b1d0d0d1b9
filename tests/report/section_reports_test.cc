// report/feedforward_report.h and report/feedback_report.h: each gain's
// value, std and unit in the text, and the same in the JSON.
#include <catch2/catch.hpp>

#include "report/feedback_report.h"
#include "report/feedforward_report.h"

using namespace driveid;

TEST_CASE("feed-forward and feedback sections: values, stds and units in text and JSON") {
  Feedforward f;
  f.effort_unit = "V";
  f.position_unit = "Radians";
  f.gains = {{"Ks", 0.125, 0.0125, "V"}, {"Kv", 3.0625, 0.02, "V s/Radians"}};
  const std::string text = FormatFeedforwardReport(f);
  for (const char* part : {"Ks", "0.125", "0.0125", "V s/Radians"}) CHECK(text.find(part) != std::string::npos);
  const Json json = FeedforwardReportJson(f);
  CHECK(json["gains"]["Kv"]["value"] == 3.0625);
  CHECK(json["gains"]["Kv"]["std"] == 0.02);
  CHECK(json["gains"]["Kv"]["unit"] == "V s/Radians");

  FeedbackController c;
  c.loop = "velocity";
  c.preset = "custom";
  c.effort_unit = "V";
  c.position_unit = "Radians";
  c.values = {{"kp", 2.11, 0.05}, {"period", 0.02, 0.0}};
  const std::string feedback = FormatFeedbackReport(c);
  for (const char* part : {"velocity", "kp", "2.11", "V s/Radians"}) CHECK(feedback.find(part) != std::string::npos);
  const Json feedback_json = FeedbackReportJson(c);
  CHECK(feedback_json["feedback"]["kp"]["value"] == 2.11);
  CHECK(feedback_json["feedback"]["kp"]["unit"] == "V s/Radians");
}
