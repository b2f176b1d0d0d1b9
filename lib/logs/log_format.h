// The log formats (docs/adding-a-model.md#adding-a-log-format): each is one
// file of logs/formats/ (or a header and a source) ending in its
// registration, DRIVEID_LOG_FORMAT(name) { return LogFormat{...}; }, and
// its name in DRIVEID_LOG_FORMATS (lib/CMakeLists.txt), which is also the
// order in which a file's first bytes are tried. Everything the rest of the
// library knows of a format is here: how it is told from its bytes, whether
// it is lines, whether it is streamed from its file, the selection options
// it takes (each refused by name on a file of another format), what
// `inspect` lists of it, and how it is opened as table sources.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "logs/table_source.h"

namespace driveid {

/// A selection option of the structured readers (a LogSelection field, by
/// its option name: "motor", "topic", "side", ...). `refusal` is what a file
/// of a format that does not take it is told: a fmt string with {option},
/// {value}, {path} and {kind} (the file's format, as "a CSV file" says it).
struct LogFormatOption {
  std::string name;
  std::string refusal;
};

/// What `inspect` lists of a format whose file holds a catalog (a WPILog's
/// entries, a bag's topics) or variables (a MAT file): the line said in
/// place of the samples, and the heading of the list's three columns.
struct LogFormatCatalog {
  std::string summary;  ///< "" for a format whose file has samples of its own (MAT)
  std::string item = "variable", count = "size", description = "address (‹col› NAME=...)";
};

using OpenLogFormat = std::function<std::vector<std::unique_ptr<TableSource>>(
    const std::string& path, const std::string& text, const CsvFormat& csv, const LogSelection& selection)>;

struct LogFormat {
  std::string name;    ///< its registration's name ("wpilog", "mcap", ...)
  std::string source;  ///< TableSource::format() of its sources ("wpilog", "rosbag", ...)
  std::string kind;    ///< as messages name a file of it: "a WPILog", "a ROS bag", "a CSV file"
  /// Whether a file is of this format, from its first bytes (at least 64, or
  /// the whole file when shorter). The last format, CSV, takes any file.
  std::function<bool(std::string_view head)> sniff;
  bool structured = false;  ///< not lines: the whole file is read without the line limit
  bool streamed = false;    ///< a bag: read from its regular file piece by piece (logs/log_files.h)
  /// The options it takes; those it declares (`declared`) carry their refusal.
  std::vector<std::string> options;
  std::vector<LogFormatOption> declared;
  LogFormatCatalog catalog;
  OpenLogFormat open;
  /// A format kept as a folder (a rosbag2 bag): the file in `folder` to read,
  /// or InputError saying why the folder is none; empty for file formats.
  std::function<std::string(const std::string& folder)> folder;
};

/// The registered formats, in DRIVEID_LOG_FORMATS' order.
const std::vector<LogFormat>& LogFormats();
/// The first format whose sniff takes `head` (CSV when none does).
const LogFormat& SniffLogFormat(std::string_view head);
/// The first format whose sources are `source` ("csv", "mat", "rosbag", ...); nullptr if none.
const LogFormat* FindLogFormatOfSource(const std::string& source);
/// How much of a file a format is told from.
inline constexpr std::size_t kLogSniffBytes = 4096;

/// Opens a file already in memory (`text` must outlive the sources) as one or more sources (a SysId file has
/// one per test, and per side with --side both). The format is the first
/// registered one whose sniff takes the file's first kLogSniffBytes (CSV
/// when none does); a selection option the format does not take is refused
/// (OptionError) with its declaring format's refusal. Throws
/// InputError naming the file.
std::vector<std::unique_ptr<TableSource>> OpenTableSources(const std::string& path, const std::string& text,
                                                           const CsvFormat& csv, const LogSelection& selection);

/// The file a log path names: itself, or for a folder the file the format
/// kept as folders finds in it (InputError when it finds none).
std::string ResolveLogPath(const std::string& path);
/// Whether a file's first chunk starts a structured log (ReadLimits::structured).
bool IsStructuredLog(std::string_view first_chunk);

/// The options of `sysid` that are set, with their values as given, in the
/// order the refusals are checked.
std::vector<std::pair<std::string, std::string>> GivenSelectionOptions(const LogSelection& selection);

/// Defines the registration of the format listed as `name` in DRIVEID_LOG_FORMATS.
#define DRIVEID_LOG_FORMAT(name) ::driveid::LogFormat MakeLogFormat_##name()

}  // namespace driveid
