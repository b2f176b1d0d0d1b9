// libFuzzer target: the CSV log reader must accept or refuse (InputError)
// any bytes, never crash, hang or throw anything else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "logs/log_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    driveid::ParseCsvLog("fuzz.csv", text, {"t", "tau_motor", "tau_link"});
  } catch (const driveid::InputError&) {
  } catch (const driveid::OptionError&) {  // e.g. a SysId drivetrain file needs --side
  }
  try {
    driveid::CsvReadOptions options;
    options.column_map = {{"psi_L", "left"}};
    driveid::ParseCsvLog("fuzz.csv", text, {"t", "psi_L", "psi_R", "tau_L|i_L", "tau_R|i_R"}, options);
  } catch (const driveid::InputError&) {
  } catch (const driveid::OptionError&) {
  }
  return 0;
}
