// libFuzzer target: the readers of real-world logs (docs/formats.md#logs) —
// MAT v5/v7.3 through libmatio, WPILib SysId JSON, header-less CSV with
// column expressions — must accept or refuse (InputError, OptionError) any
// bytes, never crash, hang or throw anything else. The first byte picks the
// reader: 0 MAT, 1 SysId JSON, 2 CSV, 3 WPILog (its catalog, then a
// routine's tests), 4 ROS bags (rosbag2 SQLite3, MCAP, ROS 1: the catalog,
// then a JointState topic's table).
#include <cstddef>
#include <cstdint>
#include <string>

#include "logs/log_format.h"
#include "logs/formats/wpilog_source.h"
#include "logs/formats/sysid_source.h"
#include "logs/formats/mat_source.h"
#include "core/errors.h"
#include "logs/log_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  driveid::LogInputOptions options;
  try {
    switch (data[0] % 5) {
      case 0: {
        const auto source = driveid::OpenMatSource("fuzz.mat", text);
        options.columns = {{"t", "data(:,1)"}, {"q", "J*data(:,2)"}, {"tau", "data(1,:)"}};
        driveid::ReadLogColumns(*source, {"t", "q", "tau|i"}, options);
        break;
      }
      case 1: {
        driveid::LogSelection sides;
        sides.sysid.side = "both";
        for (const auto& source : driveid::OpenSysIdSources("fuzz.json", text, sides)) {
          driveid::ReadLogColumns(*source, {"t", "q", "tau|i"}, options);
        }
        break;
      }
      case 3:
      case 4: {
        driveid::LogSelection format;
        format.catalog = true;
        format.bag.joints = {"axis"};
        format.bag.topic = "/joint_states";
        format.wpilog.motor = "leader";
        // The bag readers by the bag's magic, the SQLite reader for any other bytes.
        const driveid::LogFormat& sniffed = driveid::SniffLogFormat(text);
        const driveid::LogFormat* bag = &sniffed;
        if (sniffed.source != "rosbag") {
          for (const auto& f : driveid::LogFormats()) {
            if (f.name == "rosbag2-sqlite3") bag = &f;
          }
        }
        const auto sources = data[0] % 5 == 3 ? driveid::OpenWpilogSources("fuzz.log", text, format)
                                              : bag->open("fuzz.log", text, {}, format);
        for (const auto& source : sources) {
          if (source->column_names().empty()) continue;  // the catalog
          driveid::ReadLogColumns(*source, {"t", "q", "tau|i"}, options);
        }
        break;
      }
      default: {
        options.columns = {{"t", "#1"}, {"q", "pi/180*#2"}, {"tau", "10*#5"}};
        options.from = 1297.495;
        driveid::ReadLogs("fuzz.csv", text, {}, {"t", "q", "tau|i"}, options);
        break;
      }
    }
  } catch (const driveid::InputError&) {
  } catch (const driveid::OptionError&) {
  }
  return 0;
}
