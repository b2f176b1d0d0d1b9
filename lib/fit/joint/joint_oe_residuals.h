// The elastic joint's output-error residuals (docs/models.md#joint-output-error):
// per log the simulated minus measured angles, rates and shaft torque,
// weighted, each segment (multiple shooting) started from its own state,
// with the simulator's sensitivities as Jacobian.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/core/residual_model.h"
#include "fit/joint/joint_oe_segments.h"
#include "logs/joint_log.h"
#include "models/joint.h"

namespace driveid {
namespace joint_oe {

enum class Channel { kMotorAngle, kLinkAngle, kMotorRate, kLinkRate, kShaftTorque };

struct OeChannel {
  Channel kind;
  const std::vector<double>* measured = nullptr;
  double weight = 1.0;
  int first_row = 0;
  std::vector<double> weighted;  // measured x weight, for fit %
  std::string name;
};

// A segment's initial state x_i(t_s) among the fit's parameters (-1: fixed).
struct OeShot {
  OeSegment segment;
  std::array<int, 4> start_parameter{-1, -1, -1, -1};
};

struct OeLog {
  const JointLog* log = nullptr;
  std::vector<double> torque;  // n tau, link side
  std::vector<OeShot> shots;   // one per segment (multiple shooting), else the whole log
  std::vector<OeChannel> channels;
  int offset_parameter = -1;  // index of its tau_l0 among the fit's parameters
};

/// The simulator's terms: the fit's free joint terms, then the initial state.
std::vector<int> SimulatedTerms(std::vector<int> terms);
/// The logs' channels, start states and first-pass weights (`n`: the gear ratio).
std::vector<OeLog> PrepareLogs(const std::vector<JointLog>& logs, double n);
/// The weighted measurements of every channel, for fit %.
void SetWeighted(std::vector<OeLog>& oe, std::vector<FitChannel>* channels);
/// Integrator tolerances: the angles resolve the smallest measured deflection
/// spread by 1e-6, the rates the same over 1 ms.
std::array<double, 2> Tolerances(const std::vector<JointLog>& logs, double n);

class Residuals : public ResidualModel {
 public:
  /// Log i simulated whole from its first segment's start, and its shots alone.
  virtual void SimulateWhole(const double* parameters, std::size_t i, std::vector<double>* motor,
                             std::vector<double>* link) = 0;
  virtual void SimulateAngles(const double* parameters, std::size_t i, std::vector<double>* motor,
                              std::vector<double>* link) = 0;
};
/// `logs` must outlive the residuals; `columns`: the fit's parameters.
std::unique_ptr<Residuals> MakeResiduals(std::vector<OeLog>& logs, const JointParameters& fixed, std::vector<int> terms,
                                         int columns, double gear_ratio, double angle_tolerance,
                                         double rate_tolerance);

}  // namespace joint_oe
}  // namespace driveid
