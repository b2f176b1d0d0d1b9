// SysId data recorded in a WPILib DataLog (logs/formats/wpilog.h; docs/formats.md#wpilog),
// found by logs/formats/wpilog_routines.h (SysIdRoutine's names, the names
// given with ‹entry›, AdvantageKit's): the state entry (quasistatic-forward,
// quasistatic-reverse, dynamic-forward, dynamic-reverse, none; or the tests
// found from the voltage) splits the tests; the motor's voltage, position
// and velocity entries carry its samples, each at its own time, units in the
// entries' metadata. Each test
// is one source with the columns t, voltage, position, velocity: t are the
// voltage records' times, position and velocity are interpolated linearly
// to them, as SysId does, from their records within the same run (a voltage
// record without one on either side is left out, and said). A test run more than once gives its last complete
// run. Without a routine, `inspect` still lists the entries (a catalog).
#include "logs/formats/wpilog_source.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/order_statistics.h"
#include "logs/formats/wpilog.h"
#include "logs/formats/wpilog_routines.h"
#include "logs/log_format.h"
#include "logs/table_source.h"

namespace driveid {
namespace {

const char* const kTests[] = {"quasistatic-forward", "quasistatic-reverse", "dynamic-forward", "dynamic-reverse"};

// Samples of one entry (all Starts of its name), sorted by time.
struct Series {
  std::vector<double> t_us, value;
};

// One contiguous run of a test state: [begin, end) in µs; complete when a
// later state record ended it.
struct Run {
  std::int64_t begin = 0, end = 0;
  bool complete = false;
};

// A value interpolated linearly at `t` from a sorted series that spans it.
double Interpolate(const Series& s, double t) {
  const auto next = std::upper_bound(s.t_us.begin(), s.t_us.end(), t);
  const std::size_t k = static_cast<std::size_t>(next - s.t_us.begin());
  if (k == 0) return s.value.front();
  if (k == s.t_us.size()) return s.value.back();
  const double t0 = s.t_us[k - 1], t1 = s.t_us[k];
  const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
  return s.value[k - 1] + w * (s.value[k] - s.value[k - 1]);
}

// The same, only from the samples within [lo, hi) (a test's run): false
// where a neighbour lies outside, as between two runs, when the routine
// logs only while a test runs and a straight line would join the last run's
// end to this one's start.
bool InterpolateWithin(const Series& s, double t, double lo, double hi, double* value) {
  const auto next = std::lower_bound(s.t_us.begin(), s.t_us.end(), t);
  const std::size_t k = static_cast<std::size_t>(next - s.t_us.begin());
  if (k < s.t_us.size() && s.t_us[k] == t) {
    *value = s.value[k];
    return s.t_us[k] >= lo && s.t_us[k] < hi;
  }
  if (k == 0 || k == s.t_us.size() || s.t_us[k - 1] < lo || s.t_us[k] >= hi) return false;
  *value = Interpolate(s, t);
  return true;
}

// The runs of each test state, from the state records in time order.
std::map<std::string, std::vector<Run>> StateRuns(const std::vector<std::pair<std::int64_t, std::string>>& states,
                                                  std::int64_t log_end) {
  std::map<std::string, std::vector<Run>> runs;
  std::string current;
  for (const auto& [t, state] : states) {
    if (state == current) continue;
    if (!current.empty() && current != "none") {
      runs[current].back().end = t;
      runs[current].back().complete = true;
    }
    current = state;
    if (current != "none") runs[current].push_back({t, log_end + 1, false});
  }
  return runs;
}


std::string EntrySummary(const WpilogEntry& e) {
  const double span = static_cast<double>(e.last_us - e.first_us) * 1e-6;
  std::string out = fmt::format("{}, {} records", e.type, e.records);
  if (e.records > 0) out += fmt::format(", {:.3f} .. {:.3f} s", static_cast<double>(e.first_us) * 1e-6, static_cast<double>(e.last_us) * 1e-6);
  if (e.records > 1 && span > 0.0) out += fmt::format(", {:.3g} Hz", static_cast<double>(e.records - 1) / span);
  if (!e.metadata.empty()) out += fmt::format(", metadata '{}'", e.metadata.substr(0, 80));
  if (e.negative_records > 0) out += fmt::format(", {} with negative times left out", e.negative_records);
  return out;
}

// The routine's records: the state entry's strings and the motor's three
// numeric series, sorted by time.
struct RoutineData {
  std::vector<std::pair<std::int64_t, std::string>> states;
  Series voltage, position, velocity;
  std::string position_unit, velocity_unit, voltage_unit;
  std::int64_t log_end = 0;
  std::vector<std::string> notes;  ///< how the states were read or found
};

// The routine's state records (SysId's names) and, with `motor`, its three
// numeric series, sorted by time. Without a state entry, the states are
// found from the motor's voltage.
RoutineData ReadRoutine(const std::string& path, const std::string& text, const WpilogRoutine& routine,
                        const WpilogMotor* motor) {
  RoutineData data;
  std::size_t unknown_states = 0;
  const WpilogIndex index = ReadWpilog(path, text, [&](const WpilogRecord& r) {
    data.log_end = std::max(data.log_end, r.timestamp_us);
    const WpilogEntry& e = *r.entry;
    if (!routine.state.empty() && e.name == routine.state) {
      const std::string state = CanonicalSysIdState(r.payload);
      if (state.empty()) {
        ++unknown_states;
        return;
      }
      data.states.emplace_back(r.timestamp_us, state);
      return;
    }
    if (motor == nullptr) return;
    Series* series = e.name == motor->voltage    ? &data.voltage
                     : e.name == motor->position ? &data.position
                     : e.name == motor->velocity ? &data.velocity
                                                 : nullptr;
    if (series == nullptr) return;
    double value = 0.0;
    if (!WpilogNumber(e.type, r.payload, value)) {
      throw InputError(fmt::format("{}: record at offset {} of '{}' ({}): not a number of that type", path, r.offset,
                                   e.name, e.type));
    }
    if (!std::isfinite(value)) {
      throw InputError(fmt::format("{}: record at offset {} of '{}': {} is not a finite number", path, r.offset, e.name, value));
    }
    series->t_us.push_back(static_cast<double>(r.timestamp_us));
    series->value.push_back(value);
  });
  if (motor != nullptr) {
    for (const auto& e : index.entries) {
      if (e.name == motor->voltage) data.voltage_unit = e.metadata;
      if (e.name == motor->position) data.position_unit = e.metadata;
      if (e.name == motor->velocity) data.velocity_unit = e.metadata;
    }
  }
  if (unknown_states > 0) {
    data.notes.push_back(fmt::format("{} records of the state entry '{}' hold no SysId state name (left out)",
                                     unknown_states, routine.state));
  }
  std::stable_sort(data.states.begin(), data.states.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (Series* s : {&data.voltage, &data.position, &data.velocity}) {
    std::vector<std::size_t> order(s->t_us.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s->t_us[a] < s->t_us[b]; });
    Series sorted;
    for (std::size_t i : order) {
      sorted.t_us.push_back(s->t_us[i]);
      sorted.value.push_back(s->value[i]);
    }
    *s = std::move(sorted);
  }
  if (routine.state.empty()) data.states = StatesFromVoltage(data.voltage.t_us, data.voltage.value, data.notes);
  return data;
}

// One test's columns from its chosen run; notes say what was taken.
std::vector<std::vector<double>> TestColumns(const RoutineData& data, const Run& run, std::vector<std::string>& notes) {
  std::vector<std::vector<double>> columns(4);
  std::vector<double> lags;
  std::size_t outside = 0, repeated = 0, unbracketed = 0;
  const double lo = std::max(data.position.t_us.front(), data.velocity.t_us.front());
  const double hi = std::min(data.position.t_us.back(), data.velocity.t_us.back());
  for (std::size_t k = 0; k < data.voltage.t_us.size(); ++k) {
    const double t = data.voltage.t_us[k];
    if (t < static_cast<double>(run.begin) || t >= static_cast<double>(run.end)) continue;
    if (t < lo || t > hi) {
      ++outside;
      continue;
    }
    if (!columns[0].empty() && t / 1e6 <= columns[0].back()) {
      ++repeated;
      continue;
    }
    double position = 0.0, velocity = 0.0;
    const auto begin = static_cast<double>(run.begin), end = static_cast<double>(run.end);
    if (!InterpolateWithin(data.position, t, begin, end, &position) ||
        !InterpolateWithin(data.velocity, t, begin, end, &velocity)) {
      ++unbracketed;
      continue;
    }
    columns[0].push_back(t / 1e6);  // the nearest double to the time (t < 2^53 exactly), as a CSV's text is read
    columns[1].push_back(data.voltage.value[k]);
    columns[2].push_back(position);
    columns[3].push_back(velocity);
    const auto next = std::lower_bound(data.position.t_us.begin(), data.position.t_us.end(), t);
    if (next != data.position.t_us.end()) lags.push_back(*next - t);
  }
  if (!lags.empty()) {
    notes.push_back(fmt::format("time base: the voltage records; position and velocity interpolated linearly to their "
                                "times (as SysId does); the position was logged a median {:.0f} µs after the voltage",
                                Median(lags)));
  }
  if (outside > 0) notes.push_back(fmt::format("{} voltage records outside the position's and velocity's span left out", outside));
  if (repeated > 0) notes.push_back(fmt::format("{} voltage records at a repeated time left out", repeated));
  if (unbracketed > 0) {
    notes.push_back(fmt::format("{} voltage records without a position and velocity record of the same run on either "
                                "side left out (not interpolated across the gap between runs)",
                                unbracketed));
  }
  return columns;
}

std::string MechanismOf(const std::string& test) {
  if (test == "arm") return "Arm";
  if (test == "elevator") return "Elevator";
  return "Simple";
}

std::vector<std::unique_ptr<TableSource>> RoutineSources(const std::string& path, const std::string& text,
                                                         const WpilogRoutine& routine, const WpilogMotor& motor,
                                                         const LogSelection& format) {
  const RoutineData data = ReadRoutine(path, text, routine, &motor);
  if (data.voltage.t_us.empty() || data.position.t_us.empty() || data.velocity.t_us.empty()) {
    throw InputError(fmt::format("{}: motor '{}' of {} has no voltage, position or velocity records", path, motor.name,
                                 routine.origin));
  }
  const std::string unit = WpilogPositionUnit(data.position_unit, motor.position);
  std::vector<std::string> common = {fmt::format(
      "WPILog, {}: voltage '{}' in '{}', position '{}' in '{}' (read as {}), velocity '{}' in '{}'", routine.origin,
      motor.voltage, data.voltage_unit, motor.position, data.position_unit, unit.empty() ? "no unit" : unit,
      motor.velocity, data.velocity_unit)};
  for (const auto& note : data.notes) common.push_back(note);
  if (unit.empty()) {
    common.push_back(fmt::format("the position entry '{}' declares no unit: the fit is in the log's numbers and not "
                                 "read as SysId data in volts; name the unit with ‹unit› (Rotations, Meters, Radians)",
                                 motor.position));
  }
  if (routine.state.empty()) {
    common.push_back(fmt::format("{} no state entry: the tests were found from the voltage pattern; name SysId's state "
                                 "entry with ‹entry› state=NAME where the log has one",
                                 kReaderWarning));
  }
  if (!data.velocity_unit.empty() && data.velocity_unit != data.position_unit + " per Second") {
    common.push_back(fmt::format("{} the velocity's unit '{}' is not the position's '{}' per second", kReaderWarning,
                                 data.velocity_unit, data.position_unit));
  }
  const auto runs = StateRuns(data.states, data.log_end);
  struct Taken {
    std::string test;
    std::vector<std::vector<double>> columns;
    std::vector<std::string> notes;
  };
  std::vector<Taken> taken;
  std::vector<std::string> missing;
  for (const char* test : kTests) {
    const auto found = runs.find(test);
    if (found == runs.end()) {
      missing.push_back(test);
      continue;
    }
    const std::vector<Run>& all = found->second;
    auto chosen = std::find_if(all.rbegin(), all.rend(), [](const Run& r) { return r.complete; });
    std::vector<std::string> notes = common;
    if (chosen == all.rend()) {
      chosen = all.rbegin();
      notes.push_back(fmt::format("{} the test never ended before the log did: its last run is taken as it stands",
                                  kReaderWarning));
    }
    const std::size_t number = static_cast<std::size_t>(all.rend() - chosen);
    const double end = chosen->complete ? static_cast<double>(chosen->end) * 1e-6 : static_cast<double>(data.log_end) * 1e-6;
    notes.push_back(fmt::format("test {}: run {} of {} ({:.3f} .. {:.3f} s){}", test, number, all.size(),
                                static_cast<double>(chosen->begin) * 1e-6, end,
                                all.size() > 1 ? "; the test ran more than once: its last complete run is used" : ""));
    auto columns = TestColumns(data, *chosen, notes);
    if (columns[0].size() < 2) {
      missing.push_back(fmt::format("{} ({} samples)", test, columns[0].size()));
      continue;
    }
    taken.push_back({test, std::move(columns), std::move(notes)});
  }
  if (taken.empty()) {
    throw InputError(fmt::format("{}: {} holds no test with samples of motor '{}'", path, routine.origin, motor.name));
  }
  std::vector<std::unique_ptr<TableSource>> out;
  for (auto& t : taken) {
    if (!missing.empty()) t.notes.push_back(fmt::format("{} no test {} in the log", kReaderWarning, fmt::join(missing, ", ")));
    out.push_back(MakeMemorySource({path, t.test, "wpilog", unit, MechanismOf(format.wpilog.test), {"t", "voltage", "position", "velocity"},
                                    std::move(t.columns), std::move(t.notes), SysIdDefaults(), {}}));
  }
  return out;
}

const WpilogRoutine& ChooseRoutine(const std::vector<WpilogRoutine>& routines, const LogSelection& format,
                                   const std::string& path) {
  std::vector<std::string> mechanisms;
  for (const auto& r : routines) mechanisms.push_back(r.mechanism);
  if (routines.size() == 1 && format.wpilog.mechanism.empty()) return routines.front();
  const std::string mechanism = ChooseName(mechanisms, format.wpilog.mechanism, "SysIdRoutine", "mechanism", path);
  return *std::find_if(routines.begin(), routines.end(), [&](const WpilogRoutine& r) { return r.mechanism == mechanism; });
}

const WpilogMotor& ChooseMotor(const WpilogRoutine& routine, const LogSelection& format, const std::string& path) {
  std::vector<std::string> names;
  for (const auto& m : routine.motors) names.push_back(m.name);
  if (routine.motors.size() == 1 && format.wpilog.motor.empty()) return routine.motors.front();
  const std::string motor = ChooseName(names, format.wpilog.motor, "motor", "motor", path);
  return *std::find_if(routine.motors.begin(), routine.motors.end(), [&](const WpilogMotor& m) { return m.name == motor; });
}

}  // namespace

std::vector<std::unique_ptr<TableSource>> OpenWpilogSources(const std::string& path, const std::string& text,
                                                            const LogSelection& format) {
  const WpilogIndex index = ReadWpilog(path, text);
  if (format.catalog) {
    std::vector<SourceVariable> variables;
    for (const auto& e : index.entries) variables.push_back({e.name, e.records, 1, EntrySummary(e)});
    std::vector<std::string> notes = {fmt::format("WPILog version {}.{}, {} entries, {} records{}", index.version >> 8,
                                                  index.version & 0xff, index.entries.size(), index.records,
                                                  index.orphan_records > 0
                                                      ? fmt::format(", {} of no started entry", index.orphan_records)
                                                      : "")};
    std::vector<WpilogRoutine> routines;
    try {
      routines = FindWpilogRoutines(path, index, format.wpilog);
    } catch (const std::exception& e) {
      notes.push_back(fmt::format("{} {}", kReaderWarning, e.what()));
    }
    for (const auto& r : routines) {
      std::vector<std::string> motors;
      for (const auto& m : r.motors) motors.push_back(m.name);
      notes.push_back(fmt::format("{}{}: motors {} (‹motor›)", r.origin,
                                  r.mechanism.empty() ? std::string() : std::string(" (‹mechanism›)"),
                                  motors.empty() ? std::string("none") : fmt::format("{}", fmt::join(motors, ", "))));
    }
    if (routines.empty()) {
      notes.push_back("no SysId routine recognised (no string entry sysid-test-state-<mechanism>, no AdvantageKit "
                      "...SysIdState with its motors' entries): name the entries with ‹entry› voltage=NAME ‹entry› "
                      "position=NAME ‹entry› velocity=NAME [‹entry› state=NAME]");
    }
    for (const auto& r : routines) {
      if (r.state.empty() || r.motors.empty()) continue;
      const RoutineData data = ReadRoutine(path, text, r, nullptr);
      for (const auto& [test, runs] : StateRuns(data.states, data.log_end)) {
        std::vector<std::string> spans;
        for (const Run& run : runs) {
          spans.push_back(fmt::format("{:.3f} .. {:.3f} s{}", static_cast<double>(run.begin) * 1e-6,
                                      static_cast<double>(run.complete ? run.end : data.log_end) * 1e-6,
                                      run.complete ? "" : " (not ended)"));
        }
        notes.push_back(fmt::format("'{}' test {}: {} run{} ({})", r.mechanism, test, runs.size(), runs.size() > 1 ? "s" : "",
                                    fmt::join(spans, ", ")));
      }
    }
    std::vector<std::unique_ptr<TableSource>> out;
    out.push_back(MakeMemorySource({path, "", "wpilog", "", "", {}, {}, std::move(notes), {}, std::move(variables)}));
    // The tests as a fit would read them, when the routine and motor are clear.
    if (!routines.empty()) {
      try {
        const WpilogRoutine& routine = ChooseRoutine(routines, format, path);
        if (!routine.motors.empty()) {
          for (auto& source : RoutineSources(path, text, routine, ChooseMotor(routine, format, path), format)) {
            out.push_back(std::move(source));
          }
        }
      } catch (const OptionError&) {
      } catch (const InputError&) {
      }
    }
    return out;
  }
  const std::vector<WpilogRoutine> routines = FindWpilogRoutines(path, index, format.wpilog);
  if (routines.empty()) {
    throw InputError(fmt::format("{}: a WPILib DataLog without a recognised SysId routine (no string entry "
                                 "sysid-test-state-<mechanism>, no AdvantageKit ...SysIdState with its motors' "
                                 "entries): name the entries with ‹entry› voltage=NAME ‹entry› position=NAME ‹entry› "
                                 "velocity=NAME [‹entry› state=NAME]; inspect lists its {} entries",
                                 path, index.entries.size()));
  }
  const WpilogRoutine& routine = ChooseRoutine(routines, format, path);
  if (routine.motors.empty()) {
    throw InputError(fmt::format("{}: {} has no motor with voltage-, position- and velocity- entries", path,
                                 routine.origin));
  }
  return RoutineSources(path, text, routine, ChooseMotor(routine, format, path), format);
}

DRIVEID_LOG_FORMAT(wpilog_source) {
  LogFormat format;
  format.name = "wpilog";
  format.source = "wpilog";
  format.kind = "a WPILog";
  format.sniff = LooksLikeWpilog;
  format.structured = true;
  const std::string refusal = "‹{option}›: {path} is no WPILog; ‹{option}› chooses in a SysIdRoutine's .wpilog";
  for (const char* option : {"mechanism", "motor", "test", "entry"}) {
    format.options.push_back(option);
    format.declared.push_back({option, refusal});
  }
  format.catalog = {"the log's entries; a SysIdRoutine's tests follow as the sources a fit reads", "entry", "records",
                    "type, records, span, mean rate over the span, metadata"};
  format.open = [](const std::string& path, const std::string& text, const CsvFormat&, const LogSelection& selection) {
    return OpenWpilogSources(path, text, selection);
  };
  return format;
}

}  // namespace driveid
