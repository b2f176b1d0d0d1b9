// What the structured readers select in a file (the --side, --motor,
// --topic, ... flags), one struct per format family that reads it, so that a
// format's options travel with it and nowhere else: a SysId JSON's side, a
// WPILog's routine and motor, a bag's topic, joints and time base. Which
// format takes which option, and what a file of another is told, is each
// format's registration (logs/log_format.h, LogFormat::options).
#pragma once

#include <string>
#include <vector>

namespace driveid {

/// A bag's time base by default: the messages' header stamps (the other is
/// "receive", the bag's receive times).
inline constexpr const char* kDefaultBagTime = "header";

/// A SysId JSON file (docs/formats.md#sysid-json).
struct SysIdSelection {
  std::string side;  ///< "left", "right" or "both" for the Drivetrain layout
};

/// A WPILog's entries named by the user (`--entry ROLE=NAME`: RobotPy's
/// and hand-written logs): the voltage, position and velocity entries, and
/// optionally the string entry of SysId's test states ("" = the tests are
/// found from the voltage).
struct WpilogEntries {
  std::string voltage, position, velocity, state;
  bool Any() const { return !voltage.empty() || !position.empty() || !velocity.empty() || !state.empty(); }
};

/// The roles `--entry` takes, in WpilogEntries' order.
inline constexpr const char* kWpilogEntryRoles[] = {"voltage", "position", "velocity", "state"};

/// Takes one `--entry ROLE=NAME` into `entries`; OptionError for an
/// unknown role, an empty name or a role given twice.
void SetWpilogEntry(WpilogEntries& entries, const std::string& given);

/// A WPILib DataLog of SysId data (docs/formats.md#wpilog): the routine
/// (the `sysid-test-state-<mechanism>` entry) and motor, "" when the log has
/// one; the mechanism: "" or "simple", "arm", "elevator"; the test; the
/// entries when named by the user.
struct WpilogSelection {
  std::string mechanism, motor, test;
  WpilogEntries entries;
};

/// A ROS bag (docs/formats.md#ros-bags): the JointState topic ("" when the
/// bag has one), the joints whose columns are q, qd, tau by default and whose
/// messages make the rows, and the time: "header" (the stamps) or "receive"
/// (the bag's receive times).
struct BagSelection {
  std::string topic;
  std::vector<std::string> joints;
  /// A serial robot's bag: with no `joints`, every joint every message
  /// carries (as `joints` = {"all"}) instead of a refusal to choose.
  bool every_joint = false;
  std::string time = kDefaultBagTime;
  /// An elastic joint's two encoders: q_motor, qd_motor, tau from the motor
  /// joint, q_link, qd_link from the link joint (its effort is a column,
  /// J.effort, not tau_link by default).
  std::string joint_motor, joint_link;
};

/// Everything a structured reader is told.
struct LogSelection {
  SysIdSelection sysid;
  WpilogSelection wpilog;
  BagSelection bag;
  bool catalog = false;  ///< `inspect`: a WPILog or bag also gives its entries or topics
  /// A bag on a regular file (logs/log_files.h ReadLogFile): read from this
  /// path piece by piece, `text` holding its first bytes only; "" reads the
  /// bag from `text`.
  std::string stream_file;
};

}  // namespace driveid
