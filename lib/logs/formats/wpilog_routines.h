// Where a WPILog holds SysId data (docs/formats.md#wpilog): the routines a
// log offers, each a state entry and, per motor, its voltage, position and
// velocity entries. Three origins:
//  - SysIdRoutine's own names: `sysid-test-state-MECHANISM` with
//    `voltage-MOTOR-MECHANISM`, `position-…`, `velocity-…`;
//  - the names given (`--entry voltage=NAME ...`: RobotPy and hand-written
//    logging), the state entry optional;
//  - AdvantageKit's naming, recognised when unambiguous: one string entry
//    named ...SysIdState, and motors whose numeric entries share a prefix
//    before `AppliedVolts`/`Volts`/`Voltage`, `Position`, `Velocity`
//    (`/Drive/Module0/DriveAppliedVolts`, `.../DrivePositionRad`,
//    `.../DriveVelocityRadPerSec`: motor `/Drive/Module0/Drive`).
// A state entry's values are SysId's state names as SysIdRoutineLog writes
// them (`quasistatic-forward`, ..., `none`) or as the enum's name
// (`kQuasistaticForward`, `State.kDynamicReverse`: AdvantageKit's and
// RobotPy's `str(state)`). Without a state entry the tests are found from
// the voltage: a ramp from rest is quasistatic, a step dynamic, its sign
// the direction.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "logs/formats/wpilog.h"
#include "logs/log_selection.h"

namespace driveid {

/// One motor's entries.
struct WpilogMotor {
  std::string name;  ///< what ‹motor› chooses
  std::string voltage, position, velocity;
};

/// A routine: its state entry ("" = tests from the voltage) and motors.
struct WpilogRoutine {
  std::string mechanism;  ///< what ‹mechanism› chooses
  std::string state;
  std::vector<WpilogMotor> motors;
  std::string origin;  ///< how it was found, for the notes
};

/// The routines of a log: the given entries (`selection.entries`, checked:
/// InputError naming an absent entry or one of the wrong type), else the
/// SysIdRoutines, else AdvantageKit's naming when it is unambiguous.
std::vector<WpilogRoutine> FindWpilogRoutines(const std::string& path, const WpilogIndex& index,
                                              const WpilogSelection& selection);

/// SysId's test name ("quasistatic-forward", ..., "none") for a state
/// entry's value in any of the spellings above; "" for another string.
std::string CanonicalSysIdState(std::string_view value);

/// State records found from the voltage alone (times [µs], sorted), each
/// test followed by "none"; `notes` say what was found.
std::vector<std::pair<std::int64_t, std::string>> StatesFromVoltage(const std::vector<double>& t_us,
                                                                   const std::vector<double>& volts,
                                                                   std::vector<std::string>& notes);

/// The unit a parameter file takes for an entry: its metadata's WPILib unit
/// name (Meter -> Meters, Rotation -> Rotations, ...), else the name's
/// AdvantageKit suffix (...PositionRad -> Radians, ...Meters -> Meters),
/// else the metadata as written.
std::string WpilogPositionUnit(const std::string& metadata, const std::string& entry_name);

}  // namespace driveid
