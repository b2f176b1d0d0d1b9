// Elastic geared drive train in the null space of the planar robot, joint B
// fixed (seed 000 section 4, Fig. 5; docs/models.md#drive-train, corrected equations).
//
// States, all referred to the gear OUTPUT:
//   phi       = q / n_g   motor angle [rad]
//   omega     = d(phi)/dt [rad/s]
//   deflection, deflection_rate: link deflection Delta and its rate (full model only)
//
// Full model (fourth order):
//   n_g^2 Theta_motor phi'' + n_g^2 d_g phi' + k_Tg (phi - Delta) + tau_c sgn(phi') = n_g tau_motor   (13)
//   n_g^2 Theta_g Delta'' + (k_Tl + k_Tg) Delta = k_Tg phi                                          (14)
//   tau_link = k_Tl Delta                                                                           (15)
// Reduced model (Theta_g = 0): Delta = k_Tg phi / (k_Tl + k_Tg), so with
//   k_eq = k_Tl k_Tg / (k_Tl + k_Tg):
//   n_g^2 Theta_motor phi'' + n_g^2 d_g phi' + k_eq phi + tau_c sgn(phi') = n_g tau_motor,  tau_link = k_eq phi
// whose transfer function tau_link / tau_motor is eq. (16).
//
// Seed misprints corrected here (docs/models.md#drive-train): (13) prints theta_g for the
// viscous term n_g^2 d_g phi'; (14) prints k_T,k on the right for k_Tg;
// n_g^2 Theta_g is 0.043 kg m^2, not 0.413; (17) prints 0.031 s for 0.013 s
// and gain 81 for n_g = 80.
//
// Coulomb friction tau_c acts at the gear output and truly sticks: the
// friction mode is -1/+1 while sliding and 0 while stuck; a stuck drive stays
// at rest while |F| <= tau_c with F = n_g tau_motor - k_Tg (phi - Delta) the
// net torque on the motor side (referred to the output). The mode switching
// lives in sim/drivetrain_simulator; this file holds the smooth vector field
// of each mode and its derivatives.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "models/parameter_table.h"

namespace driveid {

/// Parameters of the drive train (section `drivetrain`); defaults are the paper's values.
struct DriveTrainParameters {
  double gear_ratio = 80.0;           ///< n_g [-]
  double link_stiffness = 15000.0;    ///< k_Tl, link bending stiffness [N m/rad]
  double gearbox_stiffness = 18375.0; ///< k_Tg, gearbox stiffness [N m/rad]
  double motor_inertia = 6.453e-5;    ///< Theta_motor, rotor inertia, motor side [kg m^2]
  double gearbox_inertia = 6.72e-6;   ///< Theta_g, gearbox inertia, motor side [kg m^2]
  double viscous_friction = 0.016;    ///< d_g, viscous friction at the gear input [N m s/rad]
  double coulomb_friction = 5.0;      ///< tau_c, Coulomb friction at the gear output [N m]
};

enum class DriveTrainModel { kReduced, kFull };

/// Index of each state in the state vector (the full model uses all four).
struct DriveTrainState {
  static constexpr int kMotorAngle = 0;      ///< phi [rad], gear output side
  static constexpr int kMotorRate = 1;       ///< omega = d(phi)/dt [rad/s]
  static constexpr int kDeflection = 2;      ///< Delta [rad]
  static constexpr int kDeflectionRate = 3;  ///< d(Delta)/dt [rad/s]
};

/// The parameter file's `drivetrain` section as written (optional values).
struct DriveTrainSection {
  static constexpr const char* kSectionName = "drivetrain";
  std::optional<double> gear_ratio, link_stiffness, gearbox_stiffness, motor_inertia, gearbox_inertia,
      viscous_friction, coulomb_friction;
};

/// The drive-train parameters; the step fit estimates the "step" ones.
inline const ParameterTable<DriveTrainSection, DriveTrainParameters>& DriveTrainParameterTable() {
  using S = DriveTrainSection;
  using P = DriveTrainParameters;
  static const ParameterTable<S, P> table = {
      {Spec("n_g", "n_g", "-", "gear ratio").Above(0.0).Required(), &S::gear_ratio, &P::gear_ratio},
      {Spec("k_Tl", "k_Tl", "N m/rad", "link bending stiffness").Above(0.0).Required().Fit("step"),
       &S::link_stiffness, &P::link_stiffness},
      {Spec("k_Tg", "k_Tg", "N m/rad", "gearbox stiffness").Above(0.0).Required().Fit("step"),
       &S::gearbox_stiffness, &P::gearbox_stiffness},
      {Spec("Theta_motor", "Theta_motor", "kg m^2", "motor rotor inertia, motor side").Above(0.0).Required()
           .Fit("step").FreeByDefault(),
       &S::motor_inertia, &P::motor_inertia},
      {Spec("Theta_g", "Theta_g", "kg m^2", "gearbox inertia, motor side").Fit("step"),
       &S::gearbox_inertia, &P::gearbox_inertia},
      {Spec("d_g", "d_g", "N m s/rad", "gearbox viscous friction at the gear input").Required().Fit("step")
           .FreeByDefault(),
       &S::viscous_friction, &P::viscous_friction},
      {Spec("tau_c", "tau_c", "N m", "Coulomb friction at the gear output").Required().Fit("step").FreeByDefault(),
       &S::coulomb_friction, &P::coulomb_friction},
  };
  return table;
}

/// The parameters of a section (Theta_g 0 when not given: reduced model
/// only); throws InputError naming a missing or out-of-range value.
inline DriveTrainParameters MakeDriveTrainParameters(const DriveTrainSection& section) {
  DriveTrainParameters defaults;
  defaults.gearbox_inertia = 0.0;
  return MakeModelParameters(DriveTrainParameterTable(), section, defaults, "drivetrain");
}

/// Parameters that can be estimated, in a fixed order (index into sensitivities).
enum class DriveTrainParameter : int {
  kViscousFriction = 0,  // d_g
  kMotorInertia,         // Theta_motor
  kGearboxInertia,       // Theta_g
  kLinkStiffness,        // k_Tl
  kGearboxStiffness,     // k_Tg
  kCoulombFriction,      // tau_c
};
constexpr int kDriveTrainParameterCount = static_cast<int>(DriveTrainParameter::kCoulombFriction) + 1;
static_assert(kDriveTrainParameterCount == 6, "DriveTrainParameter: the last enumerator ends the list");

/// Member of each estimable parameter (the table row is found by member).
double DriveTrainParameters::*DriveTrainParameterMember(DriveTrainParameter parameter);
/// Key of a parameter in the parameter file (`d_g`, `Theta_motor`, ...), from the table.
const char* DriveTrainParameterKey(DriveTrainParameter parameter);
/// Value of a parameter; SetDriveTrainParameter is its inverse.
double GetDriveTrainParameter(const DriveTrainParameters& params, DriveTrainParameter parameter);
void SetDriveTrainParameter(DriveTrainParameters& params, DriveTrainParameter parameter, double value);

/// Number of states: 2 (reduced) or 4 (full).
int DriveTrainStateSize(DriveTrainModel model);

/// Series stiffness k_eq = k_Tl k_Tg / (k_Tl + k_Tg) [N m/rad].
double CalcSeriesStiffness(const DriveTrainParameters& params);

/// Net torque F = n_g tau_motor - k_Tg (phi - Delta) that the friction must
/// hold (reduced: n_g tau_motor - k_eq phi) [N m, gear output].
double CalcNetTorque(const DriveTrainParameters& params, DriveTrainModel model, double motor_torque,
                     const double* state);

/// Link torque tau_link = k_Tl Delta (reduced: k_eq phi) [N m], eq. (15).
double CalcLinkTorque(const DriveTrainParameters& params, DriveTrainModel model, const double* state);

/// Link deflection Delta [rad], the gear output (link root) angle with the
/// link's far end fixed: full model the state, reduced k_Tg phi / (k_Tl + k_Tg).
double CalcDeflection(const DriveTrainParameters& params, DriveTrainModel model, const double* state);
/// d(Delta)/d(state) (row) and d(Delta)/d(parameter) at fixed state.
void CalcDeflectionStateGradient(const DriveTrainParameters& params, DriveTrainModel model, double* gradient);
double CalcDeflectionParameterDerivative(const DriveTrainParameters& params, DriveTrainModel model,
                                         const double* state, DriveTrainParameter parameter);

/// d(tau_link)/d(state) (row) and d(tau_link)/d(parameter) at fixed state.
void CalcLinkTorqueStateGradient(const DriveTrainParameters& params, DriveTrainModel model, double* gradient);
double CalcLinkTorqueParameterDerivative(const DriveTrainParameters& params, DriveTrainModel model,
                                         const double* state, DriveTrainParameter parameter);

/// State derivative in friction mode `friction_mode` (-1, +1 sliding; 0 stuck).
void CalcDriveTrainDerivatives(const DriveTrainParameters& params, DriveTrainModel model, double motor_torque,
                               int friction_mode, const double* state, double* derivative);

/// Jacobian d(derivative)/d(state), column-major n x n.
void CalcDriveTrainStateJacobian(const DriveTrainParameters& params, DriveTrainModel model, int friction_mode,
                                 double* jacobian);

/// d(derivative)/d(parameter) at fixed state (length n).
void CalcDriveTrainParameterJacobian(const DriveTrainParameters& params, DriveTrainModel model,
                                     double motor_torque, int friction_mode, const double* state,
                                     DriveTrainParameter parameter, double* column);

/// Second-order lag of eq. (16), reduced model: tau_link/tau_motor =
/// gain / (lag_s2 s^2 + lag_s1 s + 1).
struct ReducedTransferFunction {
  double gain;               ///< n_g [-] (N m per N m)
  double lag_s2;             ///< n_g^2 Theta_motor / k_eq [s^2]
  double lag_s1;             ///< n_g^2 d_g / k_eq [s]
  double natural_frequency;  ///< omega_n [rad/s]
  double damping_ratio;      ///< zeta [-]
};
ReducedTransferFunction CalcReducedTransferFunction(const DriveTrainParameters& params);

/// Undamped natural frequencies of the full model with the motor stuck
/// (Delta mode: sqrt((k_Tl + k_Tg) / (n_g^2 Theta_g))) [rad/s].
double CalcStuckLinkFrequency(const DriveTrainParameters& params);

}  // namespace driveid
