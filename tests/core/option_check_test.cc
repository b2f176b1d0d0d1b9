// The options' self-check (core/option_check.h): the first violated bound
// is the one reported, in the message the tools print; nested options are
// checked in their place; NaN and infinities never pass a bound; simulated
// sample counts are bounded from both sides.
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "core/fit_options.h"
#include "core/option_check.h"

namespace driveid {
namespace {

struct Inner {
  double gain = 1.0;
  bool IsValid(std::string* error) const {
    return OptionCheck(error).Require(Positive(gain), "‹gain›", gain, "gain > 0");
  }
};

struct Outer {
  double rate = 100.0;
  std::string method = "welch";
  Inner inner;
  double band = 1.0;
  bool IsValid(std::string* error) const {
    return OptionCheck(error)
        .Require(Positive(rate), "‹rate›", rate, "rate > 0")
        .Require(method == "welch" || method == "periodic", "‹method› " + method + ": welch or periodic")
        .Nested(inner)
        .Require(NotNegative(band), "‹band›", band, "band >= 0");
  }
};

TEST_CASE("the first violated bound is reported, nested options in their place") {
  std::string error;
  Outer ok;
  CHECK(ok.IsValid(&error));
  CHECK(error.empty());
  CHECK_NOTHROW(RequireValid(ok));

  Outer bad;
  bad.inner.gain = -2.0;
  bad.band = -1.0;  // later: not the one reported
  CHECK_FALSE(bad.IsValid(&error));
  CHECK(error == "‹gain› = -2: violated constraint: gain > 0");
  bad.method = "fft";  // earlier than the nested options
  CHECK_FALSE(bad.IsValid(&error));
  CHECK(error == "‹method› fft: welch or periodic");
  bad = Outer{};
  bad.band = -1.0;
  CHECK_THROWS_AS(RequireValid(bad), OptionError);
  CHECK_THROWS_WITH(RequireValid(bad), "‹band› = -1: violated constraint: band >= 0");
}

TEST_CASE("NaN and infinities pass no bound; zero is not positive but not negative") {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  for (double x : {nan, inf, -inf}) {
    CHECK_FALSE(Finite(x));
    CHECK_FALSE(Positive(x));
    CHECK_FALSE(NotNegative(x));
  }
  CHECK_FALSE(Positive(0.0));
  CHECK(NotNegative(0.0));
  CHECK(NotNegative(-0.0));
  CHECK_FALSE(NotNegative(-1e-300));
  CHECK(Positive(4.9e-324));
  Outer bad;
  bad.rate = nan;
  std::string error;
  CHECK_FALSE(bad.IsValid(&error));
  CHECK(error == "‹rate› = nan: violated constraint: rate > 0");
}

TEST_CASE("RequireOption, and the sample count of a simulated log from both sides") {
  CHECK_NOTHROW(RequireOption(true, "‹x›", 1.0, "x > 0"));
  CHECK_THROWS_WITH(RequireOption(false, "‹x›", -1.0, "x > 0"), "‹x› = -1: violated constraint: x > 0");
  CHECK_NOTHROW(RequireSampleCount(100.0, 100, "--duration 1 at --rate 100"));
  CHECK_NOTHROW(RequireSampleCount(kMaxSimulatedSamples, 1, "c"));
  CHECK_THROWS_WITH(RequireSampleCount(99.0, 100, "--duration 0.99 at --rate 100"),
                    Catch::Contains("--duration 0.99 at --rate 100 gives 99 samples: the fit of such a log needs at "
                                    "least 100"));
  CHECK_THROWS_WITH(RequireSampleCount(2e7, 1, "--duration 2e4"), Catch::Contains("at most 1e+07"));
  CHECK_THROWS_AS(RequireSampleCount(std::nan(""), 1, "c"), OptionError);
}

TEST_CASE("the fit options' bounds, and the large-problem line at exactly its bytes") {
  std::string error;
  FitOptions options;
  CHECK(options.IsValid(&error));
  options.max_iterations = 0;
  CHECK_FALSE(options.IsValid(&error));
  CHECK(error == "max_iterations = 0: violated constraint: >= 1");
  options = FitOptions{};
  options.identifiability_threshold = 1.0;
  CHECK_FALSE(options.IsValid(&error));
  options = FitOptions{};
  options.max_seconds = std::nan("");
  CHECK_FALSE(options.IsValid(&error));
  CHECK(error == "‹max_seconds› = nan: violated constraint: max seconds >= 0 (0: no limit)");
  LargeProblemPolicy large;
  large.jacobian_bytes = 800;
  CHECK_FALSE(large.IsLarge(25, 4));  // 800 bytes: not above
  CHECK(large.IsLarge(25, 5));
  CHECK_FALSE(LargeProblemPolicy{}.IsLarge(std::size_t{1} << 20, 2));  // 16 MiB exactly: not above
  CHECK(LargeProblemPolicy{}.IsLarge((std::size_t{1} << 20) + 1, 2));
}

}  // namespace
}  // namespace driveid
