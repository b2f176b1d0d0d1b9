// WPILib SysId JSON (the format SysId 2022 writes): an object with `test`
// ("Simple", "Elevator", "Arm", "Drivetrain"), `units`, `unitsPerRotation`
// and four tests `slow-forward`, `slow-backward` (quasistatic ramps),
// `fast-forward`, `fast-backward` (steps), each an array of samples:
//   Simple/Elevator/Arm: [t, voltage, position, velocity]
//   Drivetrain: [t, left V, right V, left pos, right pos, left vel, right vel, gyro angle, gyro rate]
// Positions and velocities are in rotations; they are multiplied by
// unitsPerRotation into `units`. Each test (and side) is one source.
#include "logs/formats/sysid_source.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "models/feedforward.h"
#include "logs/log_format.h"
#include "logs/log_options.h"
#include "logs/table_source.h"

namespace driveid {
namespace {

const char* const kTests[] = {"slow-forward", "slow-backward", "fast-forward", "fast-backward"};

// What the SAX pass collects: the scalars, and each test's samples as one
// flat run of numbers with the width of its samples (all equal), so that
// the file's text is the only large thing besides the numbers themselves.
struct SysIdDocument {
  std::optional<std::string> layout, units;
  std::optional<double> per_rotation;
  struct Test {
    bool present = false;
    std::vector<double> values;
    std::size_t width = 0, samples = 0;
  };
  std::map<std::string, Test> tests;
};

// nlohmann's SAX interface: one pass over the text, no DOM (a DOM of 10^7
// samples took 23 times the file). Refuses duplicate keys at the top level,
// which a DOM would silently resolve (the last wins).
class SysIdHandler : public nlohmann::json_sax<nlohmann::json> {
 public:
  SysIdHandler(const std::string& path, SysIdDocument& doc) : path_(path), doc_(doc) {}

  bool null() override { return Scalar("null"); }
  bool boolean(bool) override { return Scalar("a boolean"); }
  bool number_integer(number_integer_t v) override { return Number(static_cast<double>(v)); }
  bool number_unsigned(number_unsigned_t v) override { return Number(static_cast<double>(v)); }
  bool number_float(number_float_t v, const string_t&) override { return Number(v); }
  bool binary(binary_t&) override { return Scalar("binary data"); }
  bool string(string_t& v) override {
    if (depth_ == 1 && (key_ == "test" || key_ == "units")) {
      if (key_ == "units" && !UnitTextProblem(v).empty()) {
        throw InputError(fmt::format("{}: 'units': not a unit name: {} (units hold letters, digits, blanks and "
                                     "/ ^ * . _ ( ) % + -)",
                                     path_, UnitTextProblem(v)));
      }
      (key_ == "test" ? doc_.layout : doc_.units) = v;
      return true;
    }
    return Scalar("a string");
  }
  bool start_object(std::size_t) override {
    if (depth_ == 0) {
      root_ = true;
    } else if (InTest()) {
      Refuse("expected an array of numbers per sample");
    }
    ++depth_;
    return true;
  }
  bool key(string_t& k) override {
    if (depth_ == 1) {
      if (!seen_.insert(k).second) {
        throw InputError(fmt::format("{}: key '{}' appears twice (JSON leaves it undefined which one counts)", path_,
                                     k.substr(0, 64)));
      }
      key_ = k;
    }
    return true;
  }
  bool end_object() override {
    --depth_;
    return true;
  }
  bool start_array(std::size_t) override {
    if (depth_ == 1 && IsTest(key_)) {
      test_ = &doc_.tests[key_];
      test_->present = true;
    } else if (InTest() && depth_ == 2) {
      count_ = 0;
    } else if (InTest()) {
      Refuse("expected numbers in a sample");
    }
    ++depth_;
    return true;
  }
  bool end_array() override {
    --depth_;
    if (InTest() && depth_ == 2) {
      if (test_->samples == 0) test_->width = count_;
      if (count_ != test_->width) {
        Refuse(fmt::format("{} numbers, the first sample has {}", count_, test_->width));
      }
      ++test_->samples;
    } else if (InTest() && depth_ == 1) {
      test_ = nullptr;
    }
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) override {
    throw InputError(fmt::format("{}: invalid JSON at byte {}{}", path_, position,
                                 e.id == 406 ? " (a number out of range)" : ""));
  }
  bool root() const { return root_; }

 private:
  bool InTest() const { return test_ != nullptr; }
  static bool IsTest(const std::string& k) {
    return std::find(std::begin(kTests), std::end(kTests), k) != std::end(kTests);
  }
  [[noreturn]] void Refuse(const std::string& what) const {
    throw InputError(fmt::format("{}: {}[{}]: {}", path_, key_, test_->samples, what));
  }
  bool Scalar(const char* what) {
    if (InTest()) Refuse(fmt::format("expected a number, found {}", what));
    if (depth_ == 1 && (key_ == "test" || key_ == "units" || key_ == "unitsPerRotation")) {
      throw InputError(fmt::format("{}: '{}': not {}", path_, key_, key_ == "unitsPerRotation" ? "a number" : "text"));
    }
    return true;
  }
  bool Number(double v) {
    if (InTest() && depth_ == 3) {
      if (!std::isfinite(v)) Refuse("not a finite number");
      test_->values.push_back(v);
      ++count_;
      return true;
    }
    if (InTest()) Refuse("expected an array of numbers per sample");
    if (depth_ == 1 && key_ == "unitsPerRotation") {
      if (!std::isfinite(v)) throw InputError(fmt::format("{}: unitsPerRotation: not a finite number", path_));
      doc_.per_rotation = v;
      return true;
    }
    return Scalar("a number");
  }

  const std::string& path_;
  SysIdDocument& doc_;
  int depth_ = 0;
  bool root_ = false;
  std::string key_;
  std::set<std::string> seen_;
  SysIdDocument::Test* test_ = nullptr;
  std::size_t count_ = 0;
};

}  // namespace

std::vector<std::unique_ptr<TableSource>> OpenSysIdSources(const std::string& path, const std::string& text,
                                                           const LogSelection& format) {
  SysIdDocument doc;
  SysIdHandler handler(path, doc);
  try {
    nlohmann::json::sax_parse(text, &handler);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", path, e.what()));
  }
  if (!handler.root() || !doc.layout) {
    throw InputError(fmt::format("{}: not a WPILib SysId file (a JSON object with 'test', 'units', "
                                 "'unitsPerRotation' and the tests slow-forward ... fast-backward)",
                                 path));
  }
  const std::string layout = *doc.layout;
  const bool drivetrain = layout == "Drivetrain" || layout == "Drivetrain (Angular)";
  if (!drivetrain && layout != "Simple" && layout != "Elevator" && layout != "Arm") {
    throw InputError(fmt::format("{}: SysId test '{}' is not one of Simple, Elevator, Arm, Drivetrain", path, layout));
  }
  if (!doc.per_rotation) throw InputError(fmt::format("{}: no 'unitsPerRotation'", path));
  const double per_rotation = *doc.per_rotation;
  if (!(per_rotation > 0.0)) throw InputError(fmt::format("{}: unitsPerRotation = {}: must be > 0", path, per_rotation));
  const std::string units = doc.units.value_or("?");
  if (units.size() > 64) {  // what a parameter file's position_unit holds
    throw InputError(fmt::format("{}: 'units' is {} bytes long: at most 64", path, units.size()));
  }

  std::vector<std::string> sides = {""};
  if (drivetrain) {
    if (format.sysid.side == "left" || format.sysid.side == "right") sides = {format.sysid.side};
    else if (format.sysid.side == "both") sides = {"left", "right"};
    else throw OptionError(fmt::format("{}: a SysId Drivetrain file: give ‹side› left, right or both", path));
  } else if (!format.sysid.side.empty()) {
    throw OptionError(fmt::format("‹side› {}: {} is a SysId '{}' file with one side", format.sysid.side, path, layout));
  }
  const std::size_t width = drivetrain ? 9 : 4;
  std::vector<std::unique_ptr<TableSource>> out;
  for (const char* test : kTests) {
    auto found = doc.tests.find(test);
    if (found == doc.tests.end() || !found->second.present) throw InputError(fmt::format("{}: no test '{}'", path, test));
    SysIdDocument::Test& samples = found->second;
    if (samples.samples > 0 && samples.width != width) {
      throw InputError(fmt::format("{}: {}[0]: expected {} numbers per sample for the {} layout, found {}", path, test,
                                   width, layout, samples.width));
    }
    std::vector<std::vector<double>> raw(width);
    for (std::size_t i = 0; i < width; ++i) {
      raw[i].resize(samples.samples);
      for (std::size_t k = 0; k < samples.samples; ++k) raw[i][k] = samples.values[k * width + i];
    }
    std::vector<double>().swap(samples.values);
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
      out.push_back(MakeMemorySource({path, side.empty() ? test : std::string(test) + "/" + side, "sysid", units, layout,
                                      std::move(names), std::move(columns), std::move(notes), SysIdDefaults(), {}}));
    }
  }
  return out;
}

namespace {

// A JSON object: '{' after a UTF-8 byte-order mark (the parser skips it too) and blanks.
bool LooksLikeJson(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  for (char c : text) {
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    return c == '{';
  }
  return false;
}

}  // namespace

DRIVEID_LOG_FORMAT(sysid_source) {
  LogFormat format;
  format.name = "sysid-json";
  format.source = "sysid";
  format.kind = "a SysId JSON file";
  format.sniff = LooksLikeJson;
  format.structured = true;  // SysId writes one long line
  format.options = {"side"};
  format.declared = {{"side", "‹{option}› {value}: {path} is {kind}; ‹{option}› applies to SysId Drivetrain files"}};
  format.open = [](const std::string& path, const std::string& text, const CsvFormat&, const LogSelection& selection) {
    return OpenSysIdSources(path, text, selection);
  };
  return format;
}

}  // namespace driveid
