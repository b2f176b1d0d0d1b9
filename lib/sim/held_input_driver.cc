#include "sim/held_input_driver.h"

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {
constexpr long kSwitchesPerSample = 4;
constexpr long kStepsPerSample = 200;
constexpr long kBudgetConstant = 2000;
}  // namespace

int RunHeldInput(CvodesIntegrator& integrator, const std::vector<double>& time, const std::vector<double>& input,
                 HeldInputSystem& system, const char* what) {
  const std::size_t samples = time.size();
  const long switch_budget = kBudgetConstant + kSwitchesPerSample * static_cast<long>(samples);
  const long step_budget = kBudgetConstant + kStepsPerSample * static_cast<long>(samples);
  long steps = 0, last_count = integrator.step_count();
  int switches = 0;
  std::size_t k = 0;
  while (k + 1 < samples) {
    std::size_t end = k + 1;
    while (end + 1 < samples && input[end] == input[k]) ++end;
    system.SetInput(input[k]);
    bool integrating = !system.Frozen();
    if (integrating) system.Restart(time[k]);
    for (std::size_t m = k + 1; m <= end; ++m) {
      if (integrating) {
        bool frozen = false;
        while (integrator.Advance(time[m], time[end])) {
          system.HandleSwitch();
          if (++switches > switch_budget) {
            throw IdentificationError(fmt::format(
                "simulation: more than {} stick/slip switches before t = {} s (chattering)", switch_budget,
                integrator.time()));
          }
          if (system.Frozen()) {
            frozen = true;
            break;
          }
          system.Restart(integrator.time());
        }
        const long total = integrator.step_count();
        steps += total - last_count;
        last_count = total;
        if (steps > step_budget) {
          throw IdentificationError(fmt::format(
              "simulation: more than {} integrator steps before t = {} s (the parameters make the {} too stiff)",
              step_budget, integrator.time(), what));
        }
        if (frozen) {
          integrating = false;  // the system holds the frozen state
        } else {
          system.CopyFromIntegrator();
        }
      }
      system.Record(m);
    }
    k = end;
  }
  return switches;
}

}  // namespace driveid
