// A term of the rigid axis model (models/axis.h, docs/models.md#axis) as an
// object, as Drake's ForceElement or Ceres's CostFunction are: it owns its
// parameters' table rows (key, paper symbol, unit, bound, fit membership),
// its force and the derivatives the fits need, and says what the tools can
// do with it — whether inverse dynamics can fit it (linear in its
// parameters), whether the simulator's exact per-sample solution holds it,
// what an export writes where the target cannot hold it. The simulator,
// both fits, the design, the exports and the validation loop over the
// registered terms (models/axis_terms.cc); adding a friction law is one
// file under models/axis_terms/ and its name in lib/CMakeLists.txt (docs/adding-a-model.md).
//
// Conventions: q [rad or m] the position, v = q' the rate, a = q'' the
// acceleration, m the direction of motion (+1, -1, 0 at rest; a simulation
// holds it through v = 0 until the friction decides, sim/axis_simulator.h).
// A term's values `p` are its parameters in the order of its rows.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/axis.h"

namespace driveid {

/// The export targets a term answers for: simulators (MJCF, URDF) and
/// WPILib's feed-forward classes (export/).
enum class AxisExportTarget { kSimulator, kWpilib };

class AxisTerm {
 public:
  virtual ~AxisTerm() = default;

  /// What messages call it: "the <name> term" ("gravity", "Coulomb").
  virtual std::string name() const = 0;
  /// Its parameters' rows. A row with neither member pointer set is stored
  /// in a slot of AxisParameters::extra, which the registry assigns.
  virtual std::vector<AxisRow> Rows() const = 0;

  /// Linear in its parameters, F = sum_i p_i phi_i(q, v, a, m): inverse
  /// dynamics fits it; otherwise only the output-error fit does.
  virtual bool linear() const = 0;
  /// Linear terms: phi_i into phi[0 .. rows).
  virtual void Regressors(double q, double v, double a, int m, double* phi) const;
  /// Linear terms: d phi_i / dq and d phi_i / dv (the simulator's Jacobian).
  virtual void RegressorSlopes(double q, double v, int m, double* d_dq, double* d_dv) const;

  /// Nonlinear terms: the force, dF/dv and dF/dp_i at the values `p`.
  virtual double Force(const double* p, double q, double v, int m) const;
  virtual double ForceRateSlope(const double* p, double q, double v, int m) const;
  virtual double ForceParameterSlope(std::size_t i, const double* p, double q, double v, int m) const;

  /// Within a direction of motion its force is affine in v and does not
  /// depend on q: while every term present is, the simulator solves each
  /// held sample in closed form (no integrator).
  virtual bool mode_affine() const { return true; }
  /// The values make its force nonzero somewhere (default: any is not 0).
  virtual bool Present(const double* p) const;
  /// The largest force it adds (the design's torque budget): a constant part
  /// and a part per unit of speed. Constant parts add up; the speed parts of
  /// terms that replace each other (a per-direction law and the plain one)
  /// do not, so the largest counts.
  virtual void ForceBound(const double* p, double* constant, double* per_rate) const;

  /// The output-error fit's checks of its start values `p` with `free` per
  /// row (InputError naming what to give).
  virtual void CheckFitStart(const double* p, const std::vector<bool>& free) const;
  /// Row of a scale parameter (v_s-like) with a plateau the output-error fit
  /// must start around: fitted from 1e-6 of its start, restarted at 1/4 and
  /// 4 times it; -1 for none.
  virtual int scale_row() const { return -1; }

  /// What an export to `target` says where it cannot hold this term ("" it
  /// can, or the exporter writes it itself).
  virtual std::string ExportNote(AxisExportTarget target) const;
};

/// Defines the factory of the term listed as `name` in DRIVEID_AXIS_TERMS
/// (lib/CMakeLists.txt), the registry's only list: the last line of the
/// term's file.
#define DRIVEID_AXIS_TERM(name, Class) \
  std::unique_ptr<AxisTerm> MakeAxisTerm_##name() { return std::make_unique<Class>(); }

/// The registered terms, in registration order (models/axis_terms.cc).
const std::vector<const AxisTerm*>& AxisTerms();

/// The term of parameter j, the row of j among the term's rows, and the
/// index of the term's first parameter (its values are contiguous there).
struct AxisTermParameter {
  const AxisTerm* term = nullptr;
  std::size_t row = 0;
  std::size_t first = 0;
};
const AxisTermParameter& AxisParameterTerm(std::size_t j);

/// The index of a term's first parameter.
std::size_t AxisFirstIndex(const AxisTerm& term);

/// "a, b and c": names joined as a sentence lists them.
std::string JoinAsList(const std::vector<std::string>& items, const char* last = " and ");

}  // namespace driveid
