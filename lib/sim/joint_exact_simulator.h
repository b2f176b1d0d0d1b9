// The exact path of the joint simulator (sim/joint_simulator.h, which
// chooses it): the joint without gravity, linear within a friction mode,
// solved per sample interval by matrix exponentials, with the same modes,
// events and sensitivity jumps (sim/joint_exact_simulator.cc).
// Documented in docs/models.md#joint-output-error.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "models/joint.h"

namespace driveid {

struct JointStateResponse;

class JointExactSimulator {
 public:
  /// `terms`: JointTerm indices (no gravity terms) whose sensitivities are computed.
  explicit JointExactSimulator(std::vector<int> terms);
  ~JointExactSimulator();
  JointExactSimulator(const JointExactSimulator&) = delete;
  JointExactSimulator& operator=(const JointExactSimulator&) = delete;

  /// As JointSimulator::Simulate; the gravity terms must be 0.
  void Simulate(const JointParameters& p, const std::vector<double>& time, const std::vector<double>& motor_torque,
                const std::array<double, 4>& x0, bool with_sensitivities, JointStateResponse* response);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace driveid
