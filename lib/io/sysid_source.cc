// WPILib SysId JSON (the format SysId 2022 writes): an object with `test`
// ("Simple", "Elevator", "Arm", "Drivetrain"), `units`, `unitsPerRotation`
// and four tests `slow-forward`, `slow-backward` (quasistatic ramps),
// `fast-forward`, `fast-backward` (steps), each an array of samples:
//   Simple/Elevator/Arm: [t, voltage, position, velocity]
//   Drivetrain: [t, left V, right V, left pos, right pos, left vel, right vel, gyro angle, gyro rate]
// Positions and velocities are in rotations; they are multiplied by
// unitsPerRotation into `units`. Each test (and side) is one source.
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "io/log_input.h"
#include "io/table_source.h"

namespace driveid {
namespace {

const char* const kTests[] = {"slow-forward", "slow-backward", "fast-forward", "fast-backward"};

class SysIdSource : public TableSource {
 public:
  SysIdSource(std::string path, std::string segment, std::string units, std::vector<std::string> names,
              std::vector<std::vector<double>> columns, std::vector<std::string> notes)
      : path_(std::move(path)), segment_(std::move(segment)), units_(std::move(units)), names_(std::move(names)),
        columns_(std::move(columns)), notes_(std::move(notes)) {}
  std::string units() const override { return units_; }
  std::string path() const override { return path_; }
  std::string segment() const override { return segment_; }
  std::string format() const override { return "sysid"; }
  std::vector<std::string> column_names() const override { return names_; }
  std::vector<std::size_t> column_lengths() const override {
    return std::vector<std::size_t>(names_.size(), columns_.empty() ? 0 : columns_.front().size());
  }
  std::vector<std::string> notes() const override { return notes_; }
  std::string DefaultReference(const std::string& logical) const override {
    if (logical == "q") return "position";
    if (logical == "tau") return "voltage";
    if (logical == "qd") return "velocity";  // the logged rate, as SysId uses it
    return {};
  }
  TableData Read(const std::vector<std::size_t>& columns) const override {
    TableData out;
    for (auto c : columns) out.columns.push_back(columns_.at(c));
    return out;
  }

 private:
  std::string path_, segment_, units_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
  std::vector<std::string> notes_;
};

double Number(const std::string& path, const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw InputError(fmt::format("{}: {}: expected a number", path, where));
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw InputError(fmt::format("{}: {}: not a finite number", path, where));
  return v;
}

}  // namespace

std::vector<std::unique_ptr<TableSource>> OpenSysIdSources(const std::string& path, const std::string& text,
                                                           const SysIdFormat& format) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text, nullptr, true, false);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: invalid JSON at byte {}", path, e.byte));
  } catch (const nlohmann::json::exception& e) {  // e.g. a number out of range (1e999)
    throw InputError(fmt::format("{}: invalid JSON: {}", path, e.what()));
  }
  if (!doc.is_object() || !doc.contains("test") || !doc["test"].is_string()) {
    throw InputError(fmt::format("{}: not a WPILib SysId file (a JSON object with 'test', 'units', "
                                 "'unitsPerRotation' and the tests slow-forward ... fast-backward)",
                                 path));
  }
  const std::string layout = doc["test"].get<std::string>();
  const bool drivetrain = layout == "Drivetrain" || layout == "Drivetrain (Angular)";
  if (!drivetrain && layout != "Simple" && layout != "Elevator" && layout != "Arm") {
    throw InputError(fmt::format("{}: SysId test '{}' is not one of Simple, Elevator, Arm, Drivetrain", path, layout));
  }
  if (!doc.contains("unitsPerRotation")) throw InputError(fmt::format("{}: no 'unitsPerRotation'", path));
  const double per_rotation = Number(path, doc["unitsPerRotation"], "unitsPerRotation");
  if (!(per_rotation > 0.0)) throw InputError(fmt::format("{}: unitsPerRotation = {}: must be > 0", path, per_rotation));
  const std::string units = doc.contains("units") && doc["units"].is_string() ? doc["units"].get<std::string>() : "?";
  if (units.size() > 64) {  // what a parameter file's position_unit holds
    throw InputError(fmt::format("{}: 'units' is {} bytes long: at most 64", path, units.size()));
  }

  std::vector<std::string> sides = {""};
  if (drivetrain) {
    if (format.side == "left" || format.side == "right") sides = {format.side};
    else if (format.side == "both") sides = {"left", "right"};
    else throw OptionError(fmt::format("{}: a SysId Drivetrain file: give --side left, right or both", path));
  } else if (!format.side.empty()) {
    throw OptionError(fmt::format("--side {}: {} is a SysId '{}' file with one side", format.side, path, layout));
  }
  const std::size_t width = drivetrain ? 9 : 4;
  std::vector<std::unique_ptr<TableSource>> out;
  for (const char* test : kTests) {
    if (!doc.contains(test)) throw InputError(fmt::format("{}: no test '{}'", path, test));
    const auto& samples = doc[test];
    if (!samples.is_array()) throw InputError(fmt::format("{}: {}: expected an array of samples", path, test));
    std::vector<std::vector<double>> raw(width);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const auto& s = samples[k];
      if (!s.is_array() || s.size() != width) {
        throw InputError(fmt::format("{}: {}[{}]: expected {} numbers per sample for the {} layout", path, test, k,
                                     width, layout));
      }
      for (std::size_t i = 0; i < width; ++i) raw[i].push_back(Number(path, s[i], fmt::format("{}[{}][{}]", test, k, i)));
    }
    for (const auto& side : sides) {
      std::vector<std::string> names = {"t", "voltage", "position", "velocity"};
      std::vector<std::vector<double>> columns;
      const std::size_t v = side == "right" ? 2 : 1, p = drivetrain ? (side == "right" ? 4 : 3) : 2,
                        w = drivetrain ? (side == "right" ? 6 : 5) : 3;
      columns = {raw[0], raw[v], raw[p], raw[w]};
      for (std::size_t c : {2, 3}) {
        for (std::size_t k = 0; k < columns[c].size(); ++k) {
          columns[c][k] *= per_rotation;
          if (!(std::abs(columns[c][k]) <= kLargestLogMagnitude)) {
            throw InputError(fmt::format("{}: unitsPerRotation = {}: {}[{}] {} x unitsPerRotation overflows (beyond "
                                         "{:g}, where a fit's sums of squares stay finite)",
                                         path, per_rotation, test, k, names[c], kLargestLogMagnitude));
          }
        }
      }
      if (drivetrain) {
        names.insert(names.end(), {"gyro", "gyro_rate"});
        columns.push_back(raw[7]);
        columns.push_back(raw[8]);
      }
      std::vector<std::string> notes = {
          fmt::format("SysId {} test, units {}: position and velocity x unitsPerRotation = {}", layout, units,
                      per_rotation)};
      out.push_back(std::make_unique<SysIdSource>(path, side.empty() ? test : std::string(test) + "/" + side, units,
                                                  std::move(names), std::move(columns), std::move(notes)));
    }
  }
  return out;
}

}  // namespace driveid
