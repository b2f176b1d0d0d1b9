#include "logs/log_format.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

// The registrations of the formats lib/CMakeLists.txt lists in
// DRIVEID_LOG_FORMATS (each defined by DRIVEID_LOG_FORMAT in its file of
// logs/formats/), in its order.
#define DRIVEID_REGISTERED_LOG_FORMAT(name) LogFormat MakeLogFormat_##name();
#include "logs/registered_log_formats.inc"
#undef DRIVEID_REGISTERED_LOG_FORMAT

namespace {

using MakeFormat = LogFormat (*)();
#define DRIVEID_REGISTERED_LOG_FORMAT(name) MakeLogFormat_##name,
const MakeFormat kRegistered[] = {
#include "logs/registered_log_formats.inc"
};
#undef DRIVEID_REGISTERED_LOG_FORMAT

std::vector<LogFormat> MakeFormats() {
  std::vector<LogFormat> formats;
  for (MakeFormat make : kRegistered) {
    LogFormat format = make();
    for (const auto& other : formats) {
      if (other.name == format.name) throw std::logic_error("log format '" + format.name + "' registered twice");
    }
    if (!format.sniff || !format.open) throw std::logic_error("log format '" + format.name + "' without sniff or open");
    formats.push_back(std::move(format));
  }
  return formats;
}

}  // namespace

const std::vector<LogFormat>& LogFormats() {
  static const std::vector<LogFormat> formats = MakeFormats();
  return formats;
}

const LogFormat& SniffLogFormat(std::string_view head) {
  for (const LogFormat& format : LogFormats()) {
    if (format.sniff(head)) return format;
  }
  throw std::logic_error("no log format takes the file (the last, CSV, takes any)");
}

const LogFormat* FindLogFormatOfSource(const std::string& source) {
  for (const LogFormat& format : LogFormats()) {
    if (format.source == source) return &format;
  }
  return nullptr;
}

std::string ResolveLogPath(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_directory(path, error)) return path;
  for (const LogFormat& format : LogFormats()) {
    if (format.folder) return format.folder(path);
  }
  return path;  // the reader says it is a directory
}

bool IsStructuredLog(std::string_view first_chunk) { return SniffLogFormat(first_chunk).structured; }

std::vector<std::unique_ptr<TableSource>> OpenTableSources(const std::string& path, const std::string& text,
                                                           const CsvFormat& csv, const LogSelection& selection) {
  const LogFormat& format = SniffLogFormat(std::string_view(text).substr(0, kLogSniffBytes));
  // An option of another format is refused by name, not ignored.
  for (const auto& [option, value] : GivenSelectionOptions(selection)) {
    if (std::find(format.options.begin(), format.options.end(), option) != format.options.end()) continue;
    for (const LogFormat& owner : LogFormats()) {
      for (const LogFormatOption& declared : owner.declared) {
        if (declared.name != option) continue;
        throw OptionError(fmt::format(fmt::runtime(declared.refusal), fmt::arg("option", option),
                                      fmt::arg("value", value), fmt::arg("path", path), fmt::arg("kind", format.kind)));
      }
    }
    throw std::logic_error("OpenTableSources: option '" + option + "' declared by no log format");
  }
  return format.open(path, text, csv, selection);
}

std::vector<std::pair<std::string, std::string>> GivenSelectionOptions(const LogSelection& selection) {
  std::vector<std::pair<std::string, std::string>> given;
  const auto text = [&](const char* name, const std::string& value) {
    if (!value.empty()) given.emplace_back(name, value);
  };
  text("mechanism", selection.wpilog.mechanism);
  text("motor", selection.wpilog.motor);
  text("test", selection.wpilog.test);
  if (selection.wpilog.entries.Any()) {
    const WpilogEntries& e = selection.wpilog.entries;
    std::vector<std::string> named;
    for (const auto& [role, name] : {std::pair<const char*, const std::string*>{"voltage", &e.voltage},
                                     {"position", &e.position}, {"velocity", &e.velocity}, {"state", &e.state}}) {
      if (!name->empty()) named.push_back(fmt::format("{}={}", role, *name));
    }
    given.emplace_back("entry", fmt::format("{}", fmt::join(named, ",")));
  }
  text("topic", selection.bag.topic);
  if (!selection.bag.joints.empty()) given.emplace_back("joint", fmt::format("{}", fmt::join(selection.bag.joints, ",")));
  text("joint_motor", selection.bag.joint_motor);
  text("joint_link", selection.bag.joint_link);
  if (selection.bag.time != kDefaultBagTime) given.emplace_back("time", selection.bag.time);
  text("side", selection.sysid.side);
  return given;
}

}  // namespace driveid
