// params/parameter_sections.h: the section registry and the helpers every
// section reads and writes with. The built-in sections come in the order
// the file writes them (DRIVEID_PARAMETER_SECTIONS), a second section of a
// name is refused, names and text are quoted so that any bytes read back,
// numbers are written to the last bit and refused where the reader would.
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "params/parameter_file.h"
#include "params/parameter_sections.h"

using namespace driveid;

TEST_CASE("parameter sections: the built-in ones in the order they are written, each once") {
  std::vector<std::string> names;
  for (const SectionHandler& s : ParameterSections()) names.push_back(s.name);
  const std::vector<std::string> expected = {"drivetrain", "planar_robot", "axis", "cdrive", "joint", "frf"};
  REQUIRE(names.size() >= expected.size() + 2);
  CHECK(std::vector<std::string>(names.begin(), names.begin() + 6) == expected);
  SectionHandler duplicate;
  duplicate.name = "axis";
  CHECK_THROWS_AS(RegisterParameterSection(duplicate), std::logic_error);
  // A section is written by its handler and read back through it.
  ParameterFile file;
  AxisSection axis;
  axis.inertia = 0.5;
  file.Set(axis);
  const std::string text = FormatParameterFile(file);
  CHECK(text.find("axis:") != std::string::npos);
  const ParameterFile back = ParseParameterFile("back.yaml", text);
  REQUIRE(back.Find<AxisSection>() != nullptr);
  CHECK(back.Find<AxisSection>()->inertia == 0.5);
}

TEST_CASE("section helpers: quoted text reads back any bytes, numbers to the last bit, refusals by name") {
  using namespace section_io;
  CHECK(Quoted("plain") == "\"plain\"");
  CHECK(Quoted("a\"b\\c") == "\"a\\\"b\\\\c\"");
  CHECK(Quoted(std::string("\x01\xff", 2)) == "\"\\x01\\xff\"");
  CHECK(Quoted("\xc3\xa9") == "\"\xc3\xa9\"");  // UTF-8 kept
  CHECK(Comment("N m/(rad/s)") == "N m/(rad/s)");
  CHECK(Comment("m\ns") == "\"m\\x0as\"");
  CHECK(YamlName("joint_1") == "joint_1");
  CHECK(YamlName("a b") == "\"a b\"");
  const double third = 1.0 / 3.0;
  CHECK(std::stod(Number(third)) == third);
  CHECK(Writable("axis.inertia", 1e-100) == 1e-100);
  CHECK_THROWS_WITH(Writable("axis.inertia", 1e-101), Catch::Contains("axis.inertia"));
  CHECK_THROWS_AS(Writable("axis.inertia", std::numeric_limits<double>::infinity()), OutputError);
}
