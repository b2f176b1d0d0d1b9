// The frequency response's section (models/frequency_response.h), its band and method.
#include <array>
#include <string>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "params/parameter_file.h"
#include "params/parameter_sections.h"

namespace driveid {
namespace {

using namespace section_io;

void ParseFrequencyResponseKey(const std::string& path, const std::string& key, const YAML::Node& value,
                               FrequencyResponseSection& section, ParameterFile&) {
  if (key == "band_hz") {
    if (!value.IsSequence() || value.size() != 2) {
      throw InputError(fmt::format("{}: frf.band_hz: expected [low, high] in Hz", Where(path, value)));
    }
    const double low = ParseNumber(path, "frf.band_hz", value[0]), high = ParseNumber(path, "frf.band_hz", value[1]);
    if (!(low >= 0.0) || !(high >= low)) {
      throw InputError(fmt::format("{}: frf.band_hz: expected 0 <= low <= high, got [{}, {}]", Where(path, value), low,
                                   high));
    }
    section.band_hz = std::array<double, 2>{low, high};
  } else if (!value.IsNull()) {  // method
    if (!value.IsScalar()) throw InputError(fmt::format("{}: frf.method: expected text", Where(path, value)));
    section.method = value.Scalar();
  }
}

std::string FormatFrequencyResponseKeys(const FrequencyResponseSection& section, const ParameterFile&) {
  std::string out;
  if (section.band_hz) {
    out += fmt::format("{:<28} # {}\n", fmt::format("  band_hz: [{}, {}]", (*section.band_hz)[0], (*section.band_hz)[1]),
                       "coherent band used [Hz]");
  }
  if (section.method) out += fmt::format("  method: {}\n", Quoted(*section.method));
  return out;
}

}  // namespace

DRIVEID_PARAMETER_SECTION(frequency_response_section) {
  return MakeSection(FrequencyResponseTable, "docs/models.md#frequency-response: measured by drivetrain-fit frf",
                     {"band_hz", "method"}, ParseFrequencyResponseKey, FormatFrequencyResponseKeys);
}

}  // namespace driveid
