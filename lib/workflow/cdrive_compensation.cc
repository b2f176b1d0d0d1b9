#include "workflow/cdrive_compensation.h"

#include "workflow/axis_feedforward.h"

namespace driveid {

Feedforward CalcCDriveCompensation(const CDriveParameters& params, const CDriveControlSettings& control,
                                   const FitResult& fit) {
  using P = CDriveParameters;
  const auto key = [](double P::*member) { return KeyOf(CDriveParameterTable(), member); };
  Feedforward out{kCDriveCompensationLaw, "N m", "rad", {}};
  const auto add = [&](const char* name, double value, std::vector<std::pair<std::string, double>> gradient) {
    out.gains.push_back({name, value, PropagateStandardError(fit, gradient), FeedforwardUnit(name, "N m", "rad")});
  };
  add("beta", params.viscous_motor, {{key(&P::viscous_motor), 1.0}});
  add("gamma_half", 0.5 * params.viscous_collar, {{key(&P::viscous_collar), 0.5}});
  add("delta", params.coulomb_motor, {{key(&P::coulomb_motor), 1.0}});
  add("eta", params.coulomb_collar, {{key(&P::coulomb_collar), 1.0}});
  add("dead_zone", control.dead_zone, {});
  add("rate_limit", control.rate_limit, {});
  return out;
}

}  // namespace driveid
