// The axis model's terms, registered in the order the parameter file writes
// them (models/axis.h): the linear terms, then the settings, then the
// nonlinear terms. The list itself is DRIVEID_AXIS_TERMS in
// lib/CMakeLists.txt: adding a term is its file under models/axis_terms/
// and its name there.
#include "models/axis_term.h"

#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "core/registered_objects.h"

namespace driveid {

// The factories of the terms lib/CMakeLists.txt lists in DRIVEID_AXIS_TERMS
// (defined by DRIVEID_AXIS_TERM in each term's file), in its order.
#define DRIVEID_REGISTERED_AXIS_TERM(name) std::unique_ptr<AxisTerm> MakeAxisTerm_##name();
#include "models/registered_axis_terms.inc"
#undef DRIVEID_REGISTERED_AXIS_TERM

namespace {

using MakeTerm = std::unique_ptr<AxisTerm> (*)();
#define DRIVEID_REGISTERED_AXIS_TERM(name) MakeAxisTerm_##name,
const MakeTerm kRegistered[] = {
#include "models/registered_axis_terms.inc"
};
#undef DRIVEID_REGISTERED_AXIS_TERM

// Settings of the axis section that are no term's: between the linear and
// the nonlinear terms' rows.
AxisTable SettingRows() {
  return {
      {Spec("k_t", "k_t", "N m/A", "torque constant for logs of current").Above(0.0), &AxisSection::torque_constant,
       nullptr},
      {Spec("n_g", "n_g", "-", "gear ratio, to report d_g = b / n_g^2").Above(0.0), &AxisSection::gear_ratio, nullptr},
      {Spec("torque_delay", "d_u", "samples",
            "when the logged torque acts after its stamp, as the fit read it (0 sampled, 0.5 held; validate reuses "
            "it; docs/models.md#torque-timing)")
           .Unbounded(),
       &AxisSection::torque_delay, nullptr},
  };
}

struct Registry {
  RegisteredObjects<AxisTerm> terms;
  AxisTable table;
  std::vector<std::size_t> row_of;  // table row of parameter j
  std::vector<AxisTermParameter> parameters;
  std::size_t linear = 0;
};

Registry Build() {
  Registry r;
  r.terms = MakeRegisteredObjects(kRegistered);
  int slot = 0;
  const auto add = [&](const AxisTerm& term) {
    const std::size_t first = r.parameters.size();
    std::size_t i = 0;
    for (AxisRow row : term.Rows()) {
      if (row.in_model == nullptr && row.in_section == nullptr) row.slot = slot++;
      if (row.slot >= static_cast<int>(kAxisExtraSlots) || r.parameters.size() >= kMaxAxisParameters) {
        throw std::logic_error("axis terms: more parameters than kAxisExtraSlots / kMaxAxisParameters hold");
      }
      r.row_of.push_back(r.table.size());
      r.table.push_back(row);
      r.parameters.push_back({&term, i++, first});
    }
  };
  for (const AxisTerm* term : r.terms.list) {
    if (term->linear()) add(*term);
  }
  r.linear = r.parameters.size();
  for (const AxisRow& row : SettingRows()) r.table.push_back(row);
  for (const AxisTerm* term : r.terms.list) {
    if (!term->linear()) add(*term);
  }
  return r;
}

const Registry& TheRegistry() {
  static const Registry registry = Build();
  return registry;
}

}  // namespace

const AxisTable& AxisParameterTable() { return TheRegistry().table; }
const std::vector<const AxisTerm*>& AxisTerms() { return TheRegistry().terms.list; }
std::size_t AxisLinearCount() { return TheRegistry().linear; }
std::size_t AxisParameterCount() { return TheRegistry().parameters.size(); }
const AxisRow& AxisTermRow(std::size_t j) { return TheRegistry().table.at(TheRegistry().row_of.at(j)); }
const AxisTermParameter& AxisParameterTerm(std::size_t j) { return TheRegistry().parameters.at(j); }

std::size_t AxisFirstIndex(const AxisTerm& term) {
  for (const auto& p : TheRegistry().parameters) {
    if (p.term == &term) return p.first;
  }
  throw std::logic_error("AxisFirstIndex: the term is not registered");
}

std::size_t AxisIndex(double AxisParameters::*member) {
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) {
    if (AxisTermRow(j).in_model == member) return j;
  }
  throw std::logic_error("AxisIndex: member not in the table");
}

std::size_t AxisIndexOf(const std::string& key) {
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) {
    if (key == AxisTermRow(j).spec.key) return j;
  }
  return AxisParameterCount();
}

AxisValues AxisValuesOf(const AxisParameters& p) {
  AxisValues out{};
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) out[j] = ModelValue(AxisTermRow(j), p);
  return out;
}

AxisValues CalcAxisRegressors(double position, double rate, double acceleration, int direction) {
  AxisValues phi{};
  const Registry& r = TheRegistry();
  for (std::size_t j = 0; j < r.linear;) {
    const AxisTerm& term = *r.parameters[j].term;
    term.Regressors(position, rate, acceleration, direction, &phi[j]);
    while (j < r.linear && r.parameters[j].term == &term) ++j;
  }
  return phi;
}

double CalcAxisForce(const AxisParameters& p, double position, double rate, double acceleration) {
  const int direction = (rate > 0.0) - (rate < 0.0);
  const AxisValues phi = CalcAxisRegressors(position, rate, acceleration, direction);
  const AxisValues values = AxisValuesOf(p);
  double tau = 0.0;
  for (std::size_t j = 0; j < AxisLinearCount(); ++j) tau += values[j] * phi[j];
  for (const AxisTerm* term : AxisTerms()) {
    if (!term->linear()) tau += term->Force(&values[AxisFirstIndex(*term)], position, rate, direction);
  }
  return tau;
}

// The defaults of a term's capabilities.
void AxisTerm::Regressors(double, double, double, int, double*) const {
  throw std::logic_error("AxisTerm::Regressors: a nonlinear term has no regressors");
}
void AxisTerm::RegressorSlopes(double, double, int, double* d_dq, double* d_dv) const {
  for (std::size_t i = 0; i < Rows().size(); ++i) d_dq[i] = d_dv[i] = 0.0;
}
double AxisTerm::Force(const double*, double, double, int) const { return 0.0; }
double AxisTerm::ForceRateSlope(const double*, double, double, int) const { return 0.0; }
double AxisTerm::ForceParameterSlope(std::size_t, const double*, double, double, int) const { return 0.0; }
bool AxisTerm::Present(const double* p) const {
  for (std::size_t i = 0; i < Rows().size(); ++i) {
    if (p[i] != 0.0) return true;
  }
  return false;
}
void AxisTerm::ForceBound(const double*, double* constant, double* per_rate) const { *constant = *per_rate = 0.0; }
void AxisTerm::CheckFitStart(const double*, const std::vector<bool>&) const {}
std::string AxisTerm::ExportNote(AxisExportTarget) const { return ""; }

std::string JoinAsList(const std::vector<std::string>& items, const char* last) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? last : ", ";
    out += items[i];
  }
  return out;
}

}  // namespace driveid
