// Elastic-joint logs (docs/formats.md#logs): t, q_motor (motor shaft angle),
// q_link (link angle), and tau (motor shaft torque; or i with joint.k_t)
// or tau_link (a torque sensor in the elastic element) or both; optional
// rates qd_motor, qd_link (output error fits them too).
#pragma once

#include <string>
#include <vector>

namespace driveid {

struct CsvLog;

struct JointLog {
  std::string path;
  std::vector<double> time;            ///< [s]
  std::vector<double> motor_position;  ///< q_motor [rad], motor shaft
  std::vector<double> link_position;   ///< q_link [rad]
  std::vector<double> torque;          ///< tau [N m], motor shaft (from i x k_t if given as current); empty: not logged
  std::vector<double> link_torque;     ///< tau_link [N m], shaft torque; empty: not logged
  std::vector<double> motor_rate;      ///< qd_motor [rad/s], motor shaft; empty: not logged
  std::vector<double> link_rate;       ///< qd_link [rad/s]; empty: not logged
};

/// A synthetic joint experiment as `simulate joint` writes it: the joint
/// log's columns plus the measured motor speed and the injected excitation.
struct JointExperimentLog {
  std::vector<double> t, tau, q_motor, qd_motor, q_link, r;
};

/// CSV text with `#` comment lines first: t,tau,q_motor,qd_motor,q_link,r.
std::string FormatJointExperimentLog(const JointExperimentLog& log, const std::vector<std::string>& comments);

/// The logical columns (an entry "a|b": a, or else b).
const std::vector<std::string>& JointLogColumns();

/// The log from columns read by ReadLogs (logs/log_input.h) with JointLogColumns().
/// Throws InputError (a current column without k_t).
JointLog MakeJointLog(CsvLog csv, double torque_constant);

}  // namespace driveid
