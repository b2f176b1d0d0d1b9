// libFuzzer target: the parameter-file reader must accept or refuse
// (InputError) any bytes, and what it accepts must format and read back.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/errors.h"
#include "params/parameter_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  driveid::ParameterFile file;
  try {
    file = driveid::ParseParameterFile("fuzz.yaml", text);
  } catch (const driveid::InputError&) {
    return 0;
  }
  const std::string formatted = driveid::FormatParameterFile(file);
  const driveid::ParameterFile again = driveid::ParseParameterFile("formatted.yaml", formatted);
  if (driveid::FormatParameterFile(again) != formatted) std::abort();  // must read back unchanged
  return 0;
}
