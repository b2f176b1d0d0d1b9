// workflow/drift_comparison.h: the relative change and z of each shared
// estimate against their closed forms; the gate drifts on either bound
// alone and on both only when both are exceeded; a file's missing estimate
// is named; a gate parameter the base lacks is refused.
#include "workflow/drift_comparison.h"
#include "report/parameter_comparison.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

ParameterEstimate Estimate(const std::string& name, double value, double std) {
  return {name, value, std, value - 2.0 * std, value + 2.0 * std, ""};
}

}  // namespace

TEST_CASE("comparison: relative change and z, the gate's bounds, missing estimates, refusals") {
  const std::vector<ParameterEstimate> base = {Estimate("J", 0.05, 0.001), Estimate("b", 0.2, 0.004),
                                               Estimate("tau_0", 0.0, 0.0)};
  const std::vector<ParameterEstimate> other = {Estimate("J", 0.053, 0.0012), Estimate("b", 0.2008, 0.003),
                                                Estimate("tau_0", 0.0, 0.0)};
  DriftGate percent;
  percent.max_percent = 5.0;
  const FileComparison by_percent = CompareEstimates("f.yaml", base, other, percent);
  REQUIRE(by_percent.parameters.size() == 3);
  const ParameterChange& j = by_percent.parameters[0];
  CHECK(j.relative_change == Approx(0.06));
  CHECK(j.z == Approx(0.003 / std::sqrt(0.001 * 0.001 + 0.0012 * 0.0012)));
  CHECK(j.drift);   // 6 % > 5 %
  CHECK_FALSE(by_percent.parameters[1].drift);  // 0.4 %
  CHECK(std::isnan(by_percent.parameters[2].relative_change));  // base 0
  CHECK(std::isnan(by_percent.parameters[2].z));                // both stds 0
  CHECK(by_percent.drift);

  DriftGate both;
  both.max_percent = 5.0;
  both.max_z = 3.0;  // J's z is 1.92: not both exceeded
  CHECK_FALSE(CompareEstimates("f.yaml", base, other, both).parameters[0].drift);
  both.max_z = 1.5;
  CHECK(CompareEstimates("f.yaml", base, other, both).parameters[0].drift);

  const FileComparison partial = CompareEstimates("g.yaml", base, {Estimate("J", 0.05, 0.001)}, {});
  CHECK(partial.missing == std::vector<std::string>{"b", "tau_0"});
  DriftGate unknown;
  unknown.parameters = {"stiffness"};
  CHECK_THROWS_AS(CompareEstimates("f.yaml", base, other, unknown), InputError);

  const std::string text = FormatComparisons("base.yaml", {by_percent, partial}, percent);
  CHECK(text.find("f.yaml") != std::string::npos);
  const Json json = ComparisonsJson("base.yaml", {by_percent}, percent);
  CHECK(json["files"][0]["parameters"]["tau_0"]["z"].is_null());
}

TEST_CASE("a gate that cannot judge says so: no estimate, a base of 0, no std on either side") {
  const std::vector<ParameterEstimate> base = {Estimate("J", 0.05, 0.001), Estimate("tau_0", 0.0, 0.01),
                                               Estimate("c", 1.0, 0.0)};
  const std::vector<ParameterEstimate> other = {Estimate("tau_0", 0.1, 0.01), Estimate("c", 1.0, 0.0)};
  DriftGate percent;
  percent.max_percent = 10.0;
  const FileComparison p = CompareEstimates("f.yaml", base, other, percent);
  CHECK_FALSE(p.drift);
  REQUIRE(p.undecided.size() == 2);
  CHECK_THAT(p.undecided[0], Catch::Contains("J: the file has no estimate"));
  CHECK_THAT(p.undecided[1], Catch::Contains("tau_0: the base value is 0"));
  DriftGate z;
  z.max_z = 3.0;
  const FileComparison q = CompareEstimates("f.yaml", base, other, z);
  REQUIRE(q.undecided.size() == 2);
  CHECK_THAT(q.undecided[1], Catch::Contains("c: neither file gives it a std"));
  // Without a gate it is a report: nothing to judge.
  CHECK(CompareEstimates("f.yaml", base, other, DriftGate{}).undecided.empty());
  CHECK_THAT(FormatComparisons("base.yaml", {p}, percent), Catch::Contains("the gate cannot judge tau_0"));
}
