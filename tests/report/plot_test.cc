// Plot styles (issue 23): measured and model distinguishable, each channel's
// pair in one hue, grey only for samples that do not count.
#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "report/plot.h"

using namespace driveid;

namespace {
std::string Colour(const std::string& style) { return style.substr(style.find("rgb '") + 5, 7); }
}  // namespace

TEST_CASE("measured points and the model line differ in colour; channels differ; the model is drawn over the points") {
  const std::vector<PlotLine> lines = {{"log1 measured", {}, {}, true},
                                       {"log1 model", {}, {}, false},
                                       {"log2 measured", {}, {}, true},
                                       {"log2 model", {}, {}, false}};
  const auto styles = LineStyles(lines);
  REQUIRE(styles.size() == 4);
  CHECK(styles[0].find("with points") == 0);
  CHECK(styles[1].find("with lines") == 0);  // listed after its points: gnuplot draws it over them
  CHECK(Colour(styles[0]) != Colour(styles[1]));
  CHECK(Colour(styles[2]) != Colour(styles[3]));
  CHECK(Colour(styles[1]) != Colour(styles[3]));  // two channels, two hues
  CHECK(Colour(styles[0]) != Colour(styles[2]));
  const std::set<std::string> colours = {Colour(styles[0]), Colour(styles[1]), Colour(styles[2]), Colour(styles[3])};
  CHECK(colours.count("#9a9a9a") == 0);  // no grey for what is fitted
}

TEST_CASE("grey only for samples that do not count; residual lines take the channels' colours in turn") {
  PlotLine grey{"coherence < 0.5", {}, {}, false, false, true};
  const auto styles = LineStyles({grey, {"measured", {}, {}, false, true}, {"model", {}, {}, false}});
  CHECK(Colour(styles[0]) == "#9a9a9a");
  CHECK(Colour(styles[1]) != Colour(styles[2]));
  const auto residuals = LineStyles({{"log1", {}, {}}, {"log2", {}, {}}});
  CHECK(Colour(residuals[0]) != Colour(residuals[1]));
}
