// The exact simulation of a drive that is linear within each friction mode
// (the elastic joint without gravity, sim/joint_exact_simulator.h; the drive
// train, sim/drivetrain_simulator.h): four states x, the second of which
// (index 1) is the rate of the body with Coulomb friction, and per mode
// m in {-1, 0, +1}
//   x' = A_m x + c_m + b_m u,   u held over each sample interval.
// Each interval is one matrix exponential
//   [x; 1; u](t + T) = exp([A c b; 0 0 0] T) [x; 1; u](t)
// and a sensitivity s_j = dx/dp_j follows s_j' = A s_j + dA_j x + dc_j + db_j u,
// the same with the 10 x 10 block matrix [[A 0 c b]; [dA_j A dc_j db_j]; 0].
// The exponentials are computed once per mode and interval length. A mode
// event inside an interval (the sliding body's rate reaching 0, the stuck
// body's static torque N leaving [-c, c]), seen at the interval's end or its
// midpoint, is located by Newton steps and bisection on the exact solution
// and handled with the jump conditions of the integrators' roots: sliding
// into rest at t*(p), s+ = s- + (f- - f+) dt*/dp with
// dt*/dp = -s_rate- / rate'-; a break-away is continuous.
// Documented in docs/models.md#joint-output-error.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace driveid {

/// The linear field of one mode, or its derivative with respect to a parameter.
struct ModeField {
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  Eigen::Vector4d c = Eigen::Vector4d::Zero(), b = Eigen::Vector4d::Zero();
};

/// What the exact simulation needs of a model.
class SwitchedLinearModel {
 public:
  virtual ~SwitchedLinearModel() = default;
  /// The field of mode -1, 0 or +1 at the current parameters.
  virtual ModeField Field(int mode) const = 0;
  /// Its derivative with respect to sensitivity j (unused for initial-state ones).
  virtual ModeField FieldDerivative(int mode, int j) const = 0;
  /// The state index sensitivity j is the initial value of, or -1 for a parameter.
  virtual int InitialStateIndex(int j) const = 0;
  /// The static torque N(x, u) the friction must hold at rest, and its rate
  /// along a state derivative dx (N is affine in x).
  virtual double StaticTorque(const Eigen::Vector4d& x, double u) const = 0;
  virtual double StaticTorqueRate(const Eigen::Vector4d& dx) const = 0;
  /// The Coulomb friction c [the static torque's unit].
  virtual double Coulomb() const = 0;
};

/// One simulation under way: Start, then Advance over each held interval.
class SwitchedLinearExact {
 public:
  static constexpr int kRate = 1;  ///< index of the rate with Coulomb friction

  /// Starts from x0 (mode from its rate, or decided at rest under u0) with
  /// `sensitivities` sensitivities (0: none); the fields are taken from
  /// `model` now. More than `switch_budget` mode switches in all throw
  /// IdentificationError (chattering).
  void Start(const SwitchedLinearModel& model, const Eigen::Vector4d& x0, double u0, int sensitivities,
             long switch_budget);
  /// Advances over an interval of `length` [s] with u held; `start` [s] is
  /// named in messages. A body at rest decides its mode under u first.
  void Advance(double length, double u, double start);

  const Eigen::Vector4d& state() const { return x_; }
  const std::vector<Eigen::Vector4d>& sensitivities() const { return s_; }
  int mode() const { return mode_; }
  long switches() const { return switches_; }

 private:
  struct Transitions {
    double length = 0.0;
    int mode = 0;
    Eigen::Matrix<double, 4, 6> state, half;  // over length and length / 2
    std::vector<Eigen::Matrix<double, 8, 10>> sensitivity;
  };
  const Transitions& Transition(double length);
  Transitions Make(double length) const;
  Eigen::Vector4d Propagate(const Eigen::Matrix<double, 4, 6>& e, const Eigen::Vector4d& x) const;
  void Apply(const Transitions& t);
  double Margin(const Eigen::Vector4d& x) const;
  bool Clear(double margin) const;
  void DecideModeAtRest();
  void AdvanceBySeries(double length);
  Eigen::Vector4d PropagateBySeries(const ModeField& f, const Eigen::Vector4d& x, double tau) const;
  double LocateEvent(double upper) const;
  double MarginRate(const Eigen::Vector4d& x, const ModeField& f) const;
  void HandleSwitch();

  const SwitchedLinearModel* model_ = nullptr;
  std::vector<int> initial_index_;  // per sensitivity
  double coulomb_ = 0.0;
  std::array<ModeField, 3> fields_;
  std::array<double, 3> radius_{};  // spectral radius of each mode's A [1/s]
  std::array<std::vector<ModeField>, 3> derivatives_;
  std::vector<Transitions> cache_;
  Eigen::Vector4d x_ = Eigen::Vector4d::Zero();
  std::vector<Eigen::Vector4d> s_;
  double u_ = 0.0;
  int mode_ = 0;
  long switches_ = 0, budget_ = 0;
};

}  // namespace driveid
