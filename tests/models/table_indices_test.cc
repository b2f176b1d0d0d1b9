// Indices kept beside the parameter tables (enums of estimable parameters,
// the axis' linear terms, the joint's simulated terms) agree with the
// tables: each index names the row it stands for, and every row a fit
// estimates has its index. A table edited without its index fails here.
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "models/axis.h"
#include "models/drivetrain.h"
#include "models/joint.h"
#include "sim/joint_simulator.h"

using namespace driveid;

TEST_CASE("DriveTrainParameter: each enumerator is a step-fit row, every step-fit row has one") {
  std::set<std::string> from_enum;
  for (int e = 0; e < kDriveTrainParameterCount; ++e) {
    const auto parameter = static_cast<DriveTrainParameter>(e);
    const std::string key = DriveTrainParameterKey(parameter);
    const auto* row = FindParameter(DriveTrainParameterTable(), key);
    REQUIRE(row != nullptr);
    CHECK(row->in_model == DriveTrainParameterMember(parameter));
    CHECK(row->spec.InFit("step"));
    CHECK(from_enum.insert(key).second);
  }
  for (const auto& row : DriveTrainParameterTable()) {
    if (row.spec.InFit("step")) CHECK(from_enum.count(row.spec.key) == 1);
  }
}

TEST_CASE("the axis' linear terms are the table's first rows, in the regressors' order") {
  const auto& table = AxisParameterTable();
  const std::size_t linear = AxisLinearCount();
  REQUIRE(table.size() > linear);
  for (const auto member : {&AxisParameters::inertia, &AxisParameters::viscous, &AxisParameters::coulomb,
                            &AxisParameters::offset, &AxisParameters::gravity_cos, &AxisParameters::gravity_sin}) {
    const std::size_t j = AxisIndex(member);
    CHECK(j < linear);
    CHECK(table[j].in_model == member);
    CHECK(&AxisTermRow(j) == &table[j]);
  }
  // Each linear row's regressor, written out here by the row's key (q 0.3,
  // q' 0.7, q'' 1.1): the regressors' order is the table's.
  const auto phi = CalcAxisRegressors(0.3, 0.7, 1.1);
  const std::map<std::string, double> expected = {
      {"inertia", 1.1},           {"viscous", 0.7},       {"coulomb", 1.0},     {"offset", 1.0},
      {"gravity_cos", std::cos(0.3)}, {"gravity_sin", std::sin(0.3)}, {"coulomb_pos", 1.0}, {"coulomb_neg", 0.0},
      {"viscous_pos", 0.7},       {"viscous_neg", 0.0}};
  std::size_t found = 0;
  for (std::size_t j = 0; j < linear; ++j) {
    INFO(table[j].spec.key);
    if (expected.count(table[j].spec.key) == 0) continue;  // a term registered since: its own test
    ++found;
    CHECK(phi[j] == Approx(expected.at(table[j].spec.key)));
  }
  CHECK(found == expected.size());
  // Past them: the settings (no model value), then the nonlinear terms'
  // parameters, stored in slots; the index of every model row is its place
  // among the model rows.
  std::size_t models = 0;
  for (std::size_t j = 0; j < table.size(); ++j) {
    if (!table[j].is_model()) {
      CHECK(j >= linear);
      continue;
    }
    CHECK(&AxisTermRow(models) == &table[j]);
    CHECK(AxisIndexOf(table[j].spec.key) == models);
    if (models >= linear) CHECK((table[j].in_model == nullptr && table[j].slot >= 0));
    ++models;
  }
  CHECK(models == AxisParameterCount());
  CHECK(AxisParameterCount() > linear);  // a nonlinear term is registered
}

TEST_CASE("the joint's simulated terms are the joint table's rows in order") {
  const auto& table = JointParameterTable();
  const std::pair<int, double JointParameters::*> terms[] = {
      {kJointMotorInertia, &JointParameters::motor_inertia}, {kJointLinkInertia, &JointParameters::link_inertia},
      {kJointStiffness, &JointParameters::stiffness},        {kJointDamping, &JointParameters::damping},
      {kJointMotorViscous, &JointParameters::motor_viscous}, {kJointMotorCoulomb, &JointParameters::motor_coulomb},
      {kJointLinkViscous, &JointParameters::link_viscous},   {kJointLinkCoulomb, &JointParameters::link_coulomb},
      {kJointOffset, &JointParameters::offset},              {kJointGravityCos, &JointParameters::gravity_cos},
      {kJointGravitySin, &JointParameters::gravity_sin}};
  for (const auto& [index, member] : terms) {
    REQUIRE(static_cast<std::size_t>(index) < table.size());
    CHECK(table[static_cast<std::size_t>(index)].in_model == member);
  }
}

TEST_CASE("ModelValuesOr: given values where the section has them, the fill elsewhere; settings untouched") {
  JointSection section;
  section.stiffness = 1200.0;
  section.motor_inertia = 0.02;
  section.torque_constant = 0.5;  // a setting, not a model parameter
  const JointParameters zero = ModelValuesOr(JointParameterTable(), section, 0.0);
  CHECK(zero.stiffness == 1200.0);
  CHECK(zero.motor_inertia == 0.02);
  CHECK(zero.damping == 0.0);
  CHECK(zero.link_inertia == 0.0);
  const JointParameters missing = ModelValuesOrNaN(JointParameterTable(), section);
  CHECK(missing.stiffness == 1200.0);
  CHECK(std::isnan(missing.damping));
  CHECK(std::isnan(missing.link_torque_offset));
}
