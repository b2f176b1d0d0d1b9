#include "common/log_input_options.h"

#include <algorithm>
#include <cstring>

#include "core/option_check.h"
#include "system/sha256.h"
#include "logs/log_format.h"
#include "logs/table_source.h"

namespace driveid::cli {

std::vector<std::string> LogCommandInputs(const std::vector<std::string>& logs, const std::string& params,
                                          const LogInputCli& input, const std::vector<std::string>& more) {
  std::vector<std::string> in = logs;
  in.push_back(params);
  in.insert(in.end(), input.join.begin(), input.join.end());
  in.insert(in.end(), more.begin(), more.end());
  return in;
}

void AddLogInputOptions(CLI::App& command, LogInputCli& options, const std::string& example) {
  command.add_option("--col", options.columns,
                     fmt::format("map a column: NAME=EXPR, EXPR a column (header name, #k position, MAT variable "
                                 "path) times or divided by numbers, pi or MAT scalars (e.g. {}; docs/formats.md)",
                                 example));
  command.add_flag("--no-header", options.no_header, "CSV: the first row is data; columns are #1, #2, ...");
  command.add_option("--skip-rows", options.skip_rows,
                     "CSV: skip this many lines before the header (a drive export's preamble; kept as comments)")
      ->check(CLI::Range(0, 1000000));
  command.add_option("--delimiter", options.delimiter, "CSV: comma, semicolon, tab or space (default: detected)")
      ->check(CLI::IsMember({"comma", "semicolon", "tab", "space", ",", ";"}));
  command.add_option("--rate", options.rate, "samples at this rate [Hz] from t = 0, for logs without a time column")
      ->check(FiniteAbove(0.0));
  command.add_option("--from", options.from, "use samples from this time on [s, log time]")->check(FiniteAtLeast(-1e300));
  command.add_option("--to", options.to, "use samples up to this time [s, log time]")->check(FiniteAtLeast(-1e300));
  command.add_option("--join", options.join,
                     "add the columns of this file row by row (positions #k count on); once, or once per log")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
  command.add_option("--join-time", options.join_time,
                     "join by time: the joined file's time column [s] (a column expression, e.g. t or stamp_ms/1000); "
                     "its columns are interpolated onto the log's time (docs/formats.md#joining-by-time)");
  command.add_option("--join-shift", options.join_shift,
                     "with --join-time: log time = joined time + SECONDS; once, or once per log")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false)
      ->check(FiniteAtLeast(-1e300));
  command.add_option("--join-align", options.join_align,
                     "with --join-time: find the shift (and a clock-rate difference) by cross-correlating a channel "
                     "both files record, LOG_COLUMN=JOINED_COLUMN (e.g. speed=#2)");
  command.add_option("--side", options.selection.sysid.side, "SysId Drivetrain files: left, right or both (two logs per test)")
      ->check(CLI::IsMember({"left", "right", "both"}));
  command.add_option("--mechanism", options.selection.wpilog.mechanism,
                     "WPILog: the SysIdRoutine (its sysid-test-state-NAME entry) when the log holds several "
                     "(docs/formats.md#wpilog)");
  command.add_option("--motor", options.selection.wpilog.motor,
                     "WPILog: the motor of the SysIdRoutine (its voltage-MOTOR-... entries) when it logs several");
  command.add_option("--test", options.selection.wpilog.test, "WPILog: the mechanism SysId would be told: simple (default), arm, elevator")
      ->check(CLI::IsMember({"simple", "arm", "elevator"}));
  command.add_option("--unit", options.unit,
                     "the unit of the position column q (e.g. Rotations, Meters, Radians) where the log declares "
                     "none, or a --col q rescales the position the log declares in another");
  command.add_option("--entry", options.entries,
                     "WPILog of any origin (RobotPy, hand-written logging): ROLE=NAME for ROLE voltage, position, "
                     "velocity and (optional) state, a string entry of SysId's state names; without state the tests "
                     "are found from the voltage (docs/formats.md#wpilog)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
  command.add_option("--topic", options.selection.bag.topic,
                     "ROS bag: the sensor_msgs/JointState topic when the bag has several (docs/formats.md#ros-bags)");
  // `validate` names an MJCF joint with --joint; there a bag's joint is a --col.
  if (command.get_option_no_throw("--joint") == nullptr) {
    command.add_option("--joint", options.selection.bag.joints,
                       "ROS bag: the joint whose position, velocity and effort are q, qd and tau (repeat for several: "
                       "their messages make the rows; map them with --col q_motor=NAME.position ...); all: every "
                       "joint as q_<joint>, qd_<joint>, tau_<joint> (robot --urdf)");
  }
  command.add_option("--joint-motor", options.selection.bag.joint_motor,
                     "ROS bag, elastic joint: the joint whose position, velocity and effort are q_motor, qd_motor and tau");
  command.add_option("--joint-link", options.selection.bag.joint_link,
                     "ROS bag, elastic joint: the joint whose position and velocity are q_link and qd_link");
  command.add_option("--time", options.selection.bag.time,
                     "ROS bag: the time base, header (the messages' stamps, default) or receive (the bag's times)")
      ->check(CLI::IsMember({"header", "receive"}));
}

LogInputOptions MakeLogInputOptions(const LogInputCli& options) {
  LogInputOptions out;
  // Each --col entry once per logical name.
  for (const auto& entry : options.columns) {
    const auto eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size()) {
      throw OptionError(fmt::format("--col {}: expected NAME=EXPR", entry));
    }
    const std::string name = entry.substr(0, eq);
    if (!out.columns.emplace(name, entry.substr(eq + 1)).second) {
      throw OptionError(fmt::format("--col {}: '{}' is mapped twice", entry, name));
    }
  }
  if (options.join.empty() && (!options.join_time.empty() || !options.join_shift.empty() || !options.join_align.empty())) {
    throw OptionError("--join-time, --join-shift and --join-align apply to a file given with --join");
  }
  out.csv.no_header = options.no_header;
  out.csv.skip_rows = static_cast<std::size_t>(options.skip_rows);
  const std::string& d = options.delimiter;
  out.csv.delimiter = d == "comma" || d == "," ? ',' : d == "semicolon" || d == ";" ? ';' : d == "tab" ? '\t'
                      : d == "space" ? ' ' : 0;
  out.selection = options.selection;
  for (const auto& entry : options.entries) SetWpilogEntry(out.selection.wpilog.entries, entry);
  out.rate = options.rate;
  out.position_unit = options.unit;
  if (std::isfinite(options.from)) out.from = options.from;
  if (std::isfinite(options.to)) out.to = options.to;
  RequireValid(out);
  return out;
}

std::string JoinFor(const LogInputCli& options, std::size_t k, std::size_t count) {
  if (options.join.empty()) return {};
  if (options.join.size() == count) return options.join[k];
  throw OptionError(fmt::format("--join given {} times for {} logs: give it once per log", options.join.size(), count));
}

JoinTiming JoinTimingFor(const LogInputCli& options, std::size_t k, std::size_t count) {
  JoinTiming timing;
  timing.time = options.join_time;
  timing.align = options.join_align;
  if (options.join_shift.size() == 1) {
    timing.shift = options.join_shift.front();
  } else if (options.join_shift.size() == count) {
    timing.shift = options.join_shift[k];
  } else if (!options.join_shift.empty()) {
    throw OptionError(fmt::format("--join-shift given {} times for {} logs: give it once, or once per log",
                                  options.join_shift.size(), count));
  }
  return timing;
}

std::vector<LogFileRequest> LogFileRequests(const LogInputCli& options, const std::vector<std::string>& paths) {
  std::vector<LogFileRequest> files;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    LogFileRequest file{paths[i], JoinFor(options, i, paths.size()), {}};
    if (!file.join_path.empty()) file.join_timing = JoinTimingFor(options, i, paths.size());
    files.push_back(std::move(file));
  }
  return files;
}

ReadLimits LogReadLimits(double max_log_gib) {
  ReadLimits limits;
  limits.structured = IsStructuredLog;  // logs may be JSON, MAT or bags
  limits.max_bytes = static_cast<std::size_t>(max_log_gib * 1073741824.0);
  limits.max_bytes_hint = fmt::format("a log may be at most {} GiB (raise with --max-log-size)", max_log_gib);
  return limits;
}

void ShowReaderWarnings(const std::vector<DataFileRecord>& records, std::size_t first) {
  std::vector<std::string> shown;
  for (std::size_t i = first; i < records.size(); ++i) {
    for (const auto& note : records[i].notes) {
      if (note.rfind(kReaderWarning, 0) != 0) continue;
      const std::string line = fmt::format("warning: {}: {}\n", records[i].file, note.substr(std::strlen(kReaderWarning) + 1));
      if (std::find(shown.begin(), shown.end(), line) != shown.end()) continue;
      shown.push_back(line);
      WriteText(stderr, line);
    }
  }
}

namespace {
thread_local const std::vector<GivenLog>* given_logs = nullptr;
}  // namespace

GivenLogsScope::GivenLogsScope(const std::vector<GivenLog>& logs) : previous_(given_logs) { given_logs = &logs; }
GivenLogsScope::~GivenLogsScope() { given_logs = previous_; }

bool HasGivenLogs() { return given_logs != nullptr; }

bool ReadGivenLog(const std::string& path, const std::vector<std::string>& columns, const LogInputOptions& options,
                  std::vector<DataFileRecord>& records, const std::function<void(CsvLog)>& take) {
  if (given_logs == nullptr) return false;
  const auto given = std::find_if(given_logs->begin(), given_logs->end(), [&](const GivenLog& g) { return g.name == path; });
  if (given == given_logs->end()) return false;
  // The record's SHA-256 is of the values as the file of a run would hold
  // them: the names, then each column's doubles in their bytes.
  std::string bytes;
  for (std::size_t k = 0; k < given->names.size(); ++k) {
    bytes += given->names[k] + '\n';
    bytes.append(reinterpret_cast<const char*>(given->columns[k].data()), given->columns[k].size() * sizeof(double));
  }
  MemorySourceParts parts;
  parts.path = given->name;
  parts.format = "arrays";
  parts.names = given->names;
  parts.columns = given->columns;
  CsvLog csv = ReadLogColumns(*MakeMemorySource(std::move(parts)), columns, options);
  records.push_back({path, Sha256Hex(bytes), static_cast<int>(csv.rows()), csv.segment, csv.notes});
  take(std::move(csv));
  return true;
}

}  // namespace driveid::cli
