#include "sim/held_input_driver.h"

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {
constexpr long kSwitchesPerSample = 4;
constexpr long kStepsPerSample = 200;
constexpr long kBudgetConstant = 2000;
}  // namespace

HeldInputRun::HeldInputRun(CvodesIntegrator& integrator, const std::vector<double>& time,
                           const std::vector<double>& input, HeldInputSystem& system, const char* what)
    : integrator_(integrator), time_(time), input_(input), system_(system), what_(what),
      switch_budget_(kBudgetConstant + kSwitchesPerSample * static_cast<long>(time.size())),
      step_budget_(kBudgetConstant + kStepsPerSample * static_cast<long>(time.size())),
      last_count_(integrator.step_count()) {}

void HeldInputRun::RunTo(std::size_t last) {
  const std::size_t samples = time_.size();
  for (; next_ <= last && next_ < samples; ++next_) {
    const std::size_t m = next_;
    if (!in_run_) {
      // A run of equal inputs from sample k = m - 1 to end_.
      const std::size_t k = m - 1;
      end_ = k + 1;
      while (end_ + 1 < samples && input_[end_] == input_[k]) ++end_;
      system_.SetInput(input_[k]);
      integrating_ = !system_.Frozen();
      if (integrating_) system_.Restart(time_[k]);
      in_run_ = true;
    }
    if (integrating_) {
      bool frozen = false;
      while (integrator_.Advance(time_[m], time_[end_])) {
        system_.HandleSwitch();
        if (++switches_ > switch_budget_) {
          throw IdentificationError(fmt::format(
              "simulation: more than {} stick/slip switches before t = {} s (chattering)", switch_budget_,
              integrator_.time()));
        }
        if (system_.Frozen()) {
          frozen = true;
          break;
        }
        system_.Restart(integrator_.time());
      }
      const long total = integrator_.step_count();
      steps_ += total - last_count_;
      last_count_ = total;
      if (steps_ > step_budget_) {
        throw IdentificationError(fmt::format(
            "simulation: more than {} integrator steps before t = {} s (the parameters make the {} too stiff)",
            step_budget_, integrator_.time(), what_));
      }
      if (frozen) {
        integrating_ = false;  // the system holds the frozen state
      } else {
        system_.CopyFromIntegrator();
      }
    }
    system_.Record(m);
    if (m == end_) in_run_ = false;
  }
}

int RunHeldInput(CvodesIntegrator& integrator, const std::vector<double>& time, const std::vector<double>& input,
                 HeldInputSystem& system, const char* what) {
  HeldInputRun run(integrator, time, input, system, what);
  if (!time.empty()) run.RunTo(time.size() - 1);
  return run.switches();
}

}  // namespace driveid
