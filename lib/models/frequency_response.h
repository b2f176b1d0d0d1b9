// What a frequency-response measurement found (docs/models.md#frequency-response),
// section `frf` of a parameter file written by `drivetrain-fit frf`:
// resonance and anti-resonance [Hz] with their std, the coherent band used
// and the estimation method. Read back for reports; not a model's input.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "models/parameter_table.h"

namespace driveid {

struct FrequencyResponseSection {
  static constexpr const char* kSectionName = "frf";
  std::optional<double> resonance_hz, resonance_hz_std, antiresonance_hz, antiresonance_hz_std;
  std::optional<std::array<double, 2>> band_hz;  ///< [low, high] of the coherent band
  std::optional<std::string> method;             ///< e.g. "periodic, 14 periods; two-mass fit"
};

/// The numeric keys (no model struct: the values are results, not parameters).
struct FrequencyResponseValues {};
inline const ParameterTable<FrequencyResponseSection, FrequencyResponseValues>& FrequencyResponseTable() {
  using S = FrequencyResponseSection;
  static const ParameterTable<S, FrequencyResponseValues> table = {
      {Spec("resonance_hz", "f_r", "Hz", "resonance sqrt(k (1/J_m + 1/J_l)) / 2 pi"),
       &S::resonance_hz, nullptr},
      {Spec("resonance_hz_std", "s_f_r", "Hz", "its standard error"),
       &S::resonance_hz_std, nullptr},
      {Spec("antiresonance_hz", "f_a", "Hz", "motor-side anti-resonance sqrt(k / J_l) / 2 pi"),
       &S::antiresonance_hz, nullptr},
      {Spec("antiresonance_hz_std", "s_f_a", "Hz", "its standard error"),
       &S::antiresonance_hz_std, nullptr},
  };
  return table;
}

}  // namespace driveid
