// Text renderings of a fit (lib/report/fit_summary.h): fit % of channels that
// (nearly) do not vary, per-log failures that say the same thing once.
#include "report/fit_summary.h"

#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fit/core/adequacy.h"

using namespace driveid;

namespace {
int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

TEST_CASE("fit %: a held channel has none, with its variation named; a varying one has its value") {
  // 7 V held with 1 % ripple; the model predicts 7 V: the NRMSE "fit" would be ~0 %.
  std::vector<double> held, held_residual, ramp, ramp_residual;
  for (int k = 0; k < 200; ++k) {
    held.push_back(7.0 + 0.07 * std::sin(0.3 * k));
    held_residual.push_back(held.back() - 7.0);
    ramp.push_back(0.01 * k);
    ramp_residual.push_back(k % 2 == 0 ? 0.01 : -0.01);
  }
  const ChannelStatistics h = DescribeResiduals("held", held.data(), held_residual.data(), 200);
  CHECK(std::isnan(h.fit_percent));
  CHECK(h.variation == Approx(0.01 / std::sqrt(2.0)).epsilon(0.05));
  CHECK_THAT(FitPercentText(h.fit_percent, h.variation), Catch::StartsWith("n/a (nearly constant: std 0.7"));
  const ChannelStatistics r = DescribeResiduals("ramp", ramp.data(), ramp_residual.data(), 200);
  CHECK(r.fit_percent == Approx(100.0 * (1.0 - 0.01 / std::sqrt((4.0 - 0.0001) / 12.0))).epsilon(0.01));
  CHECK(FitPercentText(r.fit_percent, r.variation).find("n/a") == std::string::npos);
  FitResult fit;
  fit.channels = {h, r};
  CHECK(CheckFitPercent(fit).empty());
}

TEST_CASE("per-log table: logs that all failed for one reason are one line; different reasons each theirs") {
  FitResult fit;
  for (int i = 0; i < 8; ++i) {
    fit.per_log.push_back({"test " + std::to_string(i), {},
                           "not identifiable from these logs: coulomb, offset: 1 near-null direction (smallest "
                           "singular value " + std::to_string(i) + "e-09 of the normalised Jacobian, threshold 0.001)"});
  }
  const std::string alike = FormatPerLogTable(fit);
  CHECK(Count(alike, "not identifiable") == 1);
  CHECK(alike.find("none of the 8 fits alone succeeded") != std::string::npos);
  fit.per_log[3].failure = "the solver did not converge";
  const std::string differ = FormatPerLogTable(fit);
  CHECK(Count(differ, "not identifiable") == 7);
  CHECK(Count(differ, "did not converge") == 1);
  fit.per_log[3].failure.clear();
  fit.per_log[3].estimates = {{"inertia", 0.05, 0.001}};
  CHECK(Count(FormatPerLogTable(fit), "not identifiable") == 7);
}
