// The elastic joint's terms, registered in the order the parameter file
// writes them (models/joint.h), and what is built from their columns: the
// parameter table, the identification's regressors and the linear terms'
// matrices. The list is DRIVEID_JOINT_TERMS in lib/CMakeLists.txt; a new
// term also gives its parameters members of JointParameters and
// JointSection and raises kJointTerms (docs/adding-a-model.md).
#include <memory>
#include <stdexcept>

#include "core/registered_objects.h"
#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {

#define DRIVEID_REGISTERED_JOINT_TERM(name) std::unique_ptr<JointModelTerm> MakeJointTerm_##name();
#include "models/registered_joint_terms.inc"
#undef DRIVEID_REGISTERED_JOINT_TERM

namespace {

using MakeTerm = std::unique_ptr<JointModelTerm> (*)();
#define DRIVEID_REGISTERED_JOINT_TERM(name) MakeJointTerm_##name,
const MakeTerm kRegistered[] = {
#include "models/registered_joint_terms.inc"
};
#undef DRIVEID_REGISTERED_JOINT_TERM

struct Registry {
  RegisteredObjects<JointModelTerm> terms;
  ParameterTable<JointSection, JointParameters> table;
  std::vector<JointTermParameter> parameters;  // per model parameter, table order
  std::vector<std::size_t> linear;
  std::vector<JointLinearDynamics> partials;
};

// Reads the linear parameter j's matrices off its column at unit motions:
// a unit acceleration of a mass gives that column of M, a unit rate D's, a
// unit angle K's (the columns are linear in the motion).
JointLinearDynamics Partial(const JointTermParameter& tp) {
  using Matrix = std::array<std::array<double, 2>, 2>;
  const std::size_t rows = tp.term->Rows().size();
  const auto column_of = [&](const JointMotion& x, Matrix& m, std::size_t mass) {
    std::vector<JointColumn> c(rows);
    tp.term->Columns(x, c.data());
    m[0][mass] = c[tp.row].motor;
    m[1][mass] = c[tp.row].link;
  };
  JointLinearDynamics out;
  column_of({0, 0, 1, 0, 0, 0}, out.mass, 0);
  column_of({0, 0, 0, 0, 0, 1}, out.mass, 1);
  column_of({0, 1, 0, 0, 0, 0}, out.damping, 0);
  column_of({0, 0, 0, 0, 1, 0}, out.damping, 1);
  column_of({1, 0, 0, 0, 0, 0}, out.stiffness, 0);
  column_of({0, 0, 0, 1, 0, 0}, out.stiffness, 1);
  return out;
}

Registry Build() {
  Registry r;
  r.terms = MakeRegisteredObjects(kRegistered);
  for (const JointModelTerm* term : r.terms.list) {
    std::size_t i = 0;
    for (const JointRow& row : term->Rows()) {
      r.table.push_back(row);
      r.parameters.push_back({term, i});
      r.partials.push_back({});
      if (term->Kind(i) == JointRowKind::kLinear) {
        r.linear.push_back(r.parameters.size() - 1);
        r.partials.back() = Partial(r.parameters.back());
      }
      ++i;
    }
  }
  if (r.parameters.size() != kJointTerms || r.linear.size() != kJointLinearTerms) {
    throw std::logic_error("joint terms: the registered rows do not match kJointTerms / kJointLinearTerms");
  }
  // Settings of the joint section that are no term's.
  r.table.push_back({Spec("gear_ratio", "n", "-", "gear ratio, q_motor = n theta_m").Above(0.0).Required(),
                     &JointSection::gear_ratio, nullptr});
  r.table.push_back({Spec("k_t", "k_t", "N m/A", "torque constant for logs of current").Above(0.0),
                     &JointSection::torque_constant, nullptr});
  return r;
}

const Registry& TheRegistry() {
  static const Registry registry = Build();
  return registry;
}

}  // namespace

const ParameterTable<JointSection, JointParameters>& JointParameterTable() { return TheRegistry().table; }
const std::vector<const JointModelTerm*>& JointTerms() { return TheRegistry().terms.list; }
const JointTermParameter& JointParameterTerm(std::size_t j) { return TheRegistry().parameters.at(j); }
const std::vector<std::size_t>& JointLinearParameters() { return TheRegistry().linear; }
JointLinearDynamics JointLinearPartial(std::size_t j) { return TheRegistry().partials.at(j); }

JointLinearDynamics CalcJointLinearDynamics(const JointParameters& p) {
  const Registry& r = TheRegistry();
  JointLinearDynamics out;
  for (const std::size_t j : r.linear) {
    const double value = ModelValue(r.table[j], p);
    const JointLinearDynamics& partial = r.partials[j];
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        out.mass[a][b] += value * partial.mass[a][b];
        out.damping[a][b] += value * partial.damping[a][b];
        out.stiffness[a][b] += value * partial.stiffness[a][b];
      }
    }
  }
  return out;
}

JointRegressors CalcJointRegressors(double motor_angle, double motor_rate, double motor_acceleration,
                                    double link_angle, double link_rate, double link_acceleration) {
  const JointMotion x{motor_angle, motor_rate, motor_acceleration, link_angle, link_rate, link_acceleration};
  const Registry& r = TheRegistry();
  JointRegressors out{};
  std::array<JointColumn, kJointTerms> columns{};
  for (std::size_t j = 0; j < kJointTerms;) {
    const JointModelTerm& term = *r.parameters[j].term;
    term.Columns(x, &columns[j]);
    while (j < kJointTerms && r.parameters[j].term == &term) ++j;
  }
  for (std::size_t j = 0; j < kJointTerms; ++j) {
    out.motor[j] = columns[j].motor;
    out.total[j] = columns[j].motor + columns[j].link;
    out.link[j] = columns[j].sensor;
  }
  return out;
}

}  // namespace driveid
