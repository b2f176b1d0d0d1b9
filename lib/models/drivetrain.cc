#include "models/drivetrain.h"

#include <cmath>
#include <stdexcept>

namespace driveid {
namespace {

constexpr int kPhi = DriveTrainState::kMotorAngle;
constexpr int kOmega = DriveTrainState::kMotorRate;
constexpr int kDeflection = DriveTrainState::kDeflection;
constexpr int kDeflectionRate = DriveTrainState::kDeflectionRate;

struct Lumped {
  double inertia;          // J = n_g^2 Theta_motor [kg m^2, output side]
  double damping;          // D = n_g^2 d_g [N m s/rad, output side]
  double gearbox_inertia;  // J_g = n_g^2 Theta_g
};

Lumped CalcLumped(const DriveTrainParameters& p) {
  const double n2 = p.gear_ratio * p.gear_ratio;
  return {n2 * p.motor_inertia, n2 * p.viscous_friction, n2 * p.gearbox_inertia};
}

}  // namespace

double DriveTrainParameters::*DriveTrainParameterMember(DriveTrainParameter parameter) {
  switch (parameter) {
    case DriveTrainParameter::kViscousFriction: return &DriveTrainParameters::viscous_friction;
    case DriveTrainParameter::kMotorInertia: return &DriveTrainParameters::motor_inertia;
    case DriveTrainParameter::kGearboxInertia: return &DriveTrainParameters::gearbox_inertia;
    case DriveTrainParameter::kLinkStiffness: return &DriveTrainParameters::link_stiffness;
    case DriveTrainParameter::kGearboxStiffness: return &DriveTrainParameters::gearbox_stiffness;
    case DriveTrainParameter::kCoulombFriction: return &DriveTrainParameters::coulomb_friction;
  }
  throw std::logic_error("DriveTrainParameterMember: bad parameter");
}

const char* DriveTrainParameterKey(DriveTrainParameter parameter) {
  const auto member = DriveTrainParameterMember(parameter);
  for (const auto& row : DriveTrainParameterTable()) {
    if (row.in_model == member) return row.spec.key;
  }
  throw std::logic_error("DriveTrainParameterKey: parameter missing from the table");
}

double GetDriveTrainParameter(const DriveTrainParameters& p, DriveTrainParameter parameter) {
  return p.*DriveTrainParameterMember(parameter);
}

void SetDriveTrainParameter(DriveTrainParameters& p, DriveTrainParameter parameter, double value) {
  p.*DriveTrainParameterMember(parameter) = value;
}

int DriveTrainStateSize(DriveTrainModel model) { return model == DriveTrainModel::kFull ? 4 : 2; }

double CalcSeriesStiffness(const DriveTrainParameters& p) {
  return p.link_stiffness * p.gearbox_stiffness / (p.link_stiffness + p.gearbox_stiffness);
}

double CalcNetTorque(const DriveTrainParameters& p, DriveTrainModel model, double motor_torque, const double* x) {
  const double drive = p.gear_ratio * motor_torque;
  if (model == DriveTrainModel::kFull) return drive - p.gearbox_stiffness * (x[kPhi] - x[kDeflection]);
  return drive - CalcSeriesStiffness(p) * x[kPhi];
}

double CalcLinkTorque(const DriveTrainParameters& p, DriveTrainModel model, const double* x) {
  if (model == DriveTrainModel::kFull) return p.link_stiffness * x[kDeflection];
  return CalcSeriesStiffness(p) * x[kPhi];
}

void CalcLinkTorqueStateGradient(const DriveTrainParameters& p, DriveTrainModel model, double* gradient) {
  if (model == DriveTrainModel::kFull) {
    gradient[kPhi] = 0.0;
    gradient[kOmega] = 0.0;
    gradient[kDeflection] = p.link_stiffness;
    gradient[kDeflectionRate] = 0.0;
  } else {
    gradient[kPhi] = CalcSeriesStiffness(p);
    gradient[kOmega] = 0.0;
  }
}

namespace {
// d k_eq / d k_Tl and d k_eq / d k_Tg.
double SeriesStiffnessDerivative(const DriveTrainParameters& p, DriveTrainParameter parameter) {
  const double sum = p.link_stiffness + p.gearbox_stiffness;
  if (parameter == DriveTrainParameter::kLinkStiffness) return p.gearbox_stiffness * p.gearbox_stiffness / (sum * sum);
  if (parameter == DriveTrainParameter::kGearboxStiffness) return p.link_stiffness * p.link_stiffness / (sum * sum);
  return 0.0;
}
}  // namespace

double CalcLinkTorqueParameterDerivative(const DriveTrainParameters& p, DriveTrainModel model, const double* x,
                                         DriveTrainParameter parameter) {
  if (model == DriveTrainModel::kFull) {
    return parameter == DriveTrainParameter::kLinkStiffness ? x[kDeflection] : 0.0;
  }
  return SeriesStiffnessDerivative(p, parameter) * x[kPhi];
}

double CalcDeflection(const DriveTrainParameters& p, DriveTrainModel model, const double* x) {
  if (model == DriveTrainModel::kFull) return x[kDeflection];
  return p.gearbox_stiffness / (p.link_stiffness + p.gearbox_stiffness) * x[kPhi];
}

void CalcDeflectionStateGradient(const DriveTrainParameters& p, DriveTrainModel model, double* gradient) {
  if (model == DriveTrainModel::kFull) {
    gradient[kPhi] = 0.0;
    gradient[kOmega] = 0.0;
    gradient[kDeflection] = 1.0;
    gradient[kDeflectionRate] = 0.0;
  } else {
    gradient[kPhi] = p.gearbox_stiffness / (p.link_stiffness + p.gearbox_stiffness);
    gradient[kOmega] = 0.0;
  }
}

double CalcDeflectionParameterDerivative(const DriveTrainParameters& p, DriveTrainModel model, const double* x,
                                         DriveTrainParameter parameter) {
  if (model == DriveTrainModel::kFull) return 0.0;
  // d/dk (k_Tg / (k_Tl + k_Tg)) phi.
  const double sum = p.link_stiffness + p.gearbox_stiffness;
  if (parameter == DriveTrainParameter::kLinkStiffness) return -p.gearbox_stiffness / (sum * sum) * x[kPhi];
  if (parameter == DriveTrainParameter::kGearboxStiffness) return p.link_stiffness / (sum * sum) * x[kPhi];
  return 0.0;
}

void CalcDriveTrainDerivatives(const DriveTrainParameters& p, DriveTrainModel model, double motor_torque,
                               int friction_mode, const double* x, double* dx) {
  const Lumped lumped = CalcLumped(p);
  if (friction_mode == 0) {
    dx[kPhi] = 0.0;
    dx[kOmega] = 0.0;
  } else {
    const double net = CalcNetTorque(p, model, motor_torque, x);
    dx[kPhi] = x[kOmega];
    dx[kOmega] = (net - lumped.damping * x[kOmega] - p.coulomb_friction * friction_mode) / lumped.inertia;
  }
  if (model == DriveTrainModel::kFull) {
    dx[kDeflection] = x[kDeflectionRate];
    dx[kDeflectionRate] =
        (p.gearbox_stiffness * x[kPhi] - (p.link_stiffness + p.gearbox_stiffness) * x[kDeflection]) /
        lumped.gearbox_inertia;
  }
}

void CalcDriveTrainStateJacobian(const DriveTrainParameters& p, DriveTrainModel model, int friction_mode,
                                 double* a) {
  const int n = DriveTrainStateSize(model);
  for (int i = 0; i < n * n; ++i) a[i] = 0.0;
  auto at = [&](int row, int col) -> double& { return a[col * n + row]; };
  const Lumped lumped = CalcLumped(p);
  if (friction_mode != 0) {
    at(kPhi, kOmega) = 1.0;
    at(kOmega, kOmega) = -lumped.damping / lumped.inertia;
    if (model == DriveTrainModel::kFull) {
      at(kOmega, kPhi) = -p.gearbox_stiffness / lumped.inertia;
      at(kOmega, kDeflection) = p.gearbox_stiffness / lumped.inertia;
    } else {
      at(kOmega, kPhi) = -CalcSeriesStiffness(p) / lumped.inertia;
    }
  }
  if (model == DriveTrainModel::kFull) {
    at(kDeflection, kDeflectionRate) = 1.0;
    at(kDeflectionRate, kPhi) = p.gearbox_stiffness / lumped.gearbox_inertia;
    at(kDeflectionRate, kDeflection) = -(p.link_stiffness + p.gearbox_stiffness) / lumped.gearbox_inertia;
  }
}

void CalcDriveTrainParameterJacobian(const DriveTrainParameters& p, DriveTrainModel model, double motor_torque,
                                     int friction_mode, const double* x, DriveTrainParameter parameter,
                                     double* column) {
  const int n = DriveTrainStateSize(model);
  for (int i = 0; i < n; ++i) column[i] = 0.0;
  const Lumped lumped = CalcLumped(p);
  const double n2 = p.gear_ratio * p.gear_ratio;
  if (friction_mode != 0) {
    double& domega = column[kOmega];
    switch (parameter) {
      case DriveTrainParameter::kViscousFriction:
        domega = -n2 * x[kOmega] / lumped.inertia;
        break;
      case DriveTrainParameter::kMotorInertia: {
        double dx[4];
        CalcDriveTrainDerivatives(p, model, motor_torque, friction_mode, x, dx);
        domega = -dx[kOmega] / p.motor_inertia;
        break;
      }
      case DriveTrainParameter::kCoulombFriction:
        domega = -static_cast<double>(friction_mode) / lumped.inertia;
        break;
      case DriveTrainParameter::kLinkStiffness:
      case DriveTrainParameter::kGearboxStiffness:
        if (model == DriveTrainModel::kFull) {
          if (parameter == DriveTrainParameter::kGearboxStiffness) {
            domega = -(x[kPhi] - x[kDeflection]) / lumped.inertia;
          }
        } else {
          domega = -SeriesStiffnessDerivative(p, parameter) * x[kPhi] / lumped.inertia;
        }
        break;
      case DriveTrainParameter::kGearboxInertia:
        break;
    }
  }
  if (model == DriveTrainModel::kFull) {
    double& drate = column[kDeflectionRate];
    switch (parameter) {
      case DriveTrainParameter::kGearboxInertia:
        drate = -(p.gearbox_stiffness * x[kPhi] - (p.link_stiffness + p.gearbox_stiffness) * x[kDeflection]) /
                (lumped.gearbox_inertia * p.gearbox_inertia);
        break;
      case DriveTrainParameter::kLinkStiffness:
        drate = -x[kDeflection] / lumped.gearbox_inertia;
        break;
      case DriveTrainParameter::kGearboxStiffness:
        drate = (x[kPhi] - x[kDeflection]) / lumped.gearbox_inertia;
        break;
      default:
        break;
    }
  }
}

ReducedTransferFunction CalcReducedTransferFunction(const DriveTrainParameters& p) {
  const double k_eq = CalcSeriesStiffness(p);
  const Lumped lumped = CalcLumped(p);
  ReducedTransferFunction tf{};
  tf.gain = p.gear_ratio;
  tf.lag_s2 = lumped.inertia / k_eq;
  tf.lag_s1 = lumped.damping / k_eq;
  tf.natural_frequency = 1.0 / std::sqrt(tf.lag_s2);
  tf.damping_ratio = 0.5 * tf.lag_s1 * tf.natural_frequency;
  return tf;
}

double CalcStuckLinkFrequency(const DriveTrainParameters& p) {
  return std::sqrt((p.link_stiffness + p.gearbox_stiffness) / (p.gear_ratio * p.gear_ratio * p.gearbox_inertia));
}

}  // namespace driveid
