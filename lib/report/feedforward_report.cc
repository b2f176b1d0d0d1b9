#include "report/feedforward_report.h"

#include <fmt/format.h>

namespace driveid {

std::string FormatFeedforwardReport(const Feedforward& f) {
  std::string out =
      f.law == kCDriveCompensationLaw
          ? std::string("friction compensation, eq. (31) (docs/models.md#c-drive), per motor I with the other J:\n"
                        "  tau_I = beta w_I + delta RL{sgn DZ(w_I)} + gamma_half (w_I - w_J) + eta RL{sgn DZ(w_I - w_J)}\n")
          : fmt::format("feed-forward (docs/models.md#feed-forward), u [{}] from q [{}]:\n"
                        "  u = Ks sgn(v) + Kv v + Ka a + Kg cos(q - Kg_angle) + offset   (elevator: Kg = offset)\n",
                        f.effort_unit, f.position_unit);
  for (const auto& g : f.gains) {
    out += fmt::format("  {:<12} {:>13.6g} +- {:<11.3g} {}\n", g.key, g.value, g.standard_error, g.unit);
  }
  return out;
}

Json FeedforwardReportJson(const Feedforward& f) {
  Json gains = Json::object();
  for (const auto& g : f.gains) gains[g.key] = {{"value", g.value}, {"std", g.standard_error}, {"unit", g.unit}};
  return {{"law", f.law}, {"effort_unit", f.effort_unit}, {"position_unit", f.position_unit}, {"gains", gains}};
}

}  // namespace driveid
