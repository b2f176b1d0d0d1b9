// The MJCF export loaded by MuJoCo itself (Debian's libmujoco): the joint's
// inertia, damping and friction loss, the gravity torque over a turn and
// the actuator's offset are what the axis model says (docs/export.md).
// Built only where CMake finds MuJoCo.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <string>

#include <catch2/catch.hpp>
#include <mujoco/mujoco.h>

#include "core/errors.h"
#include "export/parameter_export.h"
#include "params/parameter_file.h"
#include "sim/mujoco_axis_simulator.h"

using namespace driveid;

namespace {
struct Loaded {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  ~Loaded() {
    if (data) mj_deleteData(data);
    if (model) mj_deleteModel(model);
  }
};

void Load(const std::string& xml, Loaded& out) {
  char error[1000] = "";
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  REQUIRE(mj_makeEmptyFileVFS(&vfs, "model.xml", static_cast<int>(xml.size())) == 0);
  const int index = mj_findFileVFS(&vfs, "model.xml");
  std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs.filedata[index]));
  out.model = mj_loadXML("model.xml", &vfs, error, sizeof(error));
  mj_deleteVFS(&vfs);
  INFO("MuJoCo: " << error);
  REQUIRE(out.model != nullptr);
  out.data = mj_makeData(out.model);
}

ParameterFile Axis(const std::string& section) {
  return ParseParameterFile("axis.yaml", "axis:\n" + section +
                                             "feedforward:\n  law: axis\n  effort_unit: \"N m\"\n  position_unit: \"rad\"\n"
                                             "  Ks: {value: 1, std: 0.01}\n");
}
}  // namespace

TEST_CASE("MJCF export: MuJoCo loads it; inertia, damping, friction, gravity and offset as the axis model") {
  const double inertia = 0.05, viscous = 0.2, coulomb = 1.0, offset = 0.3, gc = 4.0, gs = -3.0;
  const ParameterFile file = Axis("  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1\n  offset: 0.3\n  gravity_cos: 4\n"
                                  "  gravity_sin: -3\n");
  ExportOptions options;
  options.joint = "shoulder";
  options.source = "axis.yaml";
  Loaded m;
  Load(ExportParameters(file, ExportTarget::kMjcf, options), m);
  REQUIRE(m.model->nv == 1);
  REQUIRE(m.model->nu == 1);
  CHECK(m.model->dof_damping[0] == Approx(viscous));
  CHECK(m.model->dof_frictionloss[0] == Approx(coulomb));
  for (double q : {-2.5, -1.0, 0.0, 0.4, 1.3, 3.0}) {
    m.data->qpos[0] = q;
    m.data->qvel[0] = 0.0;
    m.data->ctrl[0] = 2.0;
    mj_forward(m.model, m.data);
    double mass[1];
    mj_fullM(m.model, mass, m.data->qM);
    INFO("q = " << q);
    CHECK(mass[0] == Approx(inertia).epsilon(1e-9));  // armature + body about the axis
    // MuJoCo's bias force is the torque that holds the joint against gravity.
    CHECK(m.data->qfrc_bias[0] == Approx(gc * std::cos(q) + gs * std::sin(q)).margin(1e-9));
    CHECK(m.data->qfrc_actuator[0] == Approx(2.0 - offset).margin(1e-12));
  }
}

TEST_CASE("MJCF export of a linear axis: a slide joint with the mass J, no gravity torque") {
  const ParameterFile file = Axis("  inertia: 12\n  viscous: 40\n  coulomb: 15\n  offset: -20\n  linear: true\n");
  Loaded m;
  Load(ExportParameters(file, ExportTarget::kMjcf, ExportOptions{}), m);
  REQUIRE(m.model->nv == 1);
  CHECK(m.model->jnt_type[0] == mjJNT_SLIDE);
  m.data->qpos[0] = 0.3;
  mj_forward(m.model, m.data);
  double mass[1];
  mj_fullM(m.model, mass, m.data->qM);
  CHECK(mass[0] == Approx(12.0).epsilon(1e-9));
  CHECK(m.data->qfrc_bias[0] == Approx(0.0).margin(1e-9));
  CHECK(m.model->dof_damping[0] == Approx(40.0));
  CHECK(m.model->dof_frictionloss[0] == Approx(15.0));
}

TEST_CASE("MJCF export of the elastic joint: motor and link joints, the spring as a tendon, gear and offset") {
  const double jm = 0.02, jl = 0.05, k = 20.0, d = 0.05, bm = 0.1, cm = 0.2, bl = 0.07, cl = 0.1, offset = 0.05;
  const double gc = 1.5, gs = -0.5, n = 50.0;
  const ParameterFile file = ParseParameterFile(
      "joint.yaml", "joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n  link_inertia: 0.05\n  stiffness: 20\n"
                    "  damping: 0.05\n  motor_viscous: 0.1\n  motor_coulomb: 0.2\n  link_viscous: 0.07\n"
                    "  link_coulomb: 0.1\n  offset: 0.05\n  gravity_cos: 1.5\n  gravity_sin: -0.5\n");
  ExportOptions options;
  options.joint = "elbow";
  Loaded m;
  Load(ExportParameters(file, ExportTarget::kMjcf, options), m);
  REQUIRE(m.model->nv == 2);
  REQUIRE(m.model->nu == 1);
  const int motor = mj_name2id(m.model, mjOBJ_JOINT, "elbow_motor");
  const int link = mj_name2id(m.model, mjOBJ_JOINT, "elbow");
  REQUIRE(motor >= 0);
  REQUIRE(link >= 0);
  const int vm = m.model->jnt_dofadr[motor], vl = m.model->jnt_dofadr[link];
  CHECK(m.model->dof_damping[vm] == Approx(bm));
  CHECK(m.model->dof_damping[vl] == Approx(bl));
  CHECK(m.model->dof_frictionloss[vm] == Approx(cm));
  CHECK(m.model->dof_frictionloss[vl] == Approx(cl));
  for (double twist : {-0.2, 0.0, 0.15}) {
    for (double ql : {-2.0, 0.0, 0.7}) {
      const double qm = ql + twist, wm = 0.3, wl = -0.1;
      m.data->qpos[m.model->jnt_qposadr[motor]] = qm;
      m.data->qpos[m.model->jnt_qposadr[link]] = ql;
      m.data->qvel[vm] = wm;
      m.data->qvel[vl] = wl;
      m.data->ctrl[0] = 2.0;
      mj_forward(m.model, m.data);
      double mass[4];
      mj_fullM(m.model, mass, m.data->qM);
      INFO("twist " << twist << ", theta_l " << ql);
      CHECK(mass[vm * 2 + vm] == Approx(jm).epsilon(1e-9));
      CHECK(mass[vl * 2 + vl] == Approx(jl).epsilon(1e-9));
      CHECK(mass[vm * 2 + vl] == Approx(0.0).margin(1e-15));
      // The spring-damper k D + d D' between them, each viscous term on its own rate.
      const double spring = k * (qm - ql) + d * (wm - wl);
      CHECK(m.data->qfrc_passive[vm] == Approx(-spring - bm * wm).margin(1e-9));
      CHECK(m.data->qfrc_passive[vl] == Approx(spring - bl * wl).margin(1e-9));
      CHECK(m.data->qfrc_bias[vm] == Approx(0.0).margin(1e-9));
      CHECK(m.data->qfrc_bias[vl] == Approx(gc * std::cos(ql) + gs * std::sin(ql)).margin(1e-9));
      CHECK(m.data->qfrc_actuator[vm] == Approx(n * 2.0 - offset).margin(1e-9));
      CHECK(m.data->qfrc_actuator[vl] == Approx(0.0).margin(1e-15));
    }
  }
}

TEST_CASE("MJCF export: a unit that would close the XML comment leaves gravity alone; a small motor's inertia loads") {
  // Issue 36: feedforward.effort_unit written into the gravity comment. The
  // readers refuse such a unit; a file built in code still exports safely.
  ParameterFile file = Axis("  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1\n  gravity_cos: 4\n  gravity_sin: -3\n");
  for (const char* unit : {"--><option gravity=\"0 0 98.1\"/><!--", "--><include file=\"x.xml\"/><!--", "a--b-",
                           "bad\xff\xfe utf8", "nul\0byte"}) {
    file.feedforward.effort_unit = unit;
    INFO(unit);
    Loaded m;
    Load(ExportParameters(file, ExportTarget::kMjcf, ExportOptions{}), m);
    CHECK(m.model->opt.gravity[2] == Approx(-9.81));
    m.data->qpos[0] = 0.4;
    mj_forward(m.model, m.data);
    CHECK(m.data->qfrc_bias[0] == Approx(4.0 * std::cos(0.4) - 3.0 * std::sin(0.4)).margin(1e-9));
  }
  // 1e-7 kg m^2, a small motor's rotor: the body under the joint stays above MuJoCo's mjMINVAL.
  const ParameterFile small = Axis("  inertia: 1e-7\n  viscous: 1e-6\n  coulomb: 1e-5\n");
  Loaded m;
  Load(ExportParameters(small, ExportTarget::kMjcf, ExportOptions{}), m);
  mj_forward(m.model, m.data);
  double mass[1];
  mj_fullM(m.model, mass, m.data->qM);
  CHECK(mass[0] == Approx(1e-7).epsilon(1e-9));
}

TEST_CASE("a MuJoCo run its first steps project beyond the budget is refused with the projection") {
  const ParameterFile file = Axis("  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1\n");
  const std::string path =
      (std::filesystem::temp_directory_path() / ("driveid_budget." + std::to_string(::getpid()) + ".xml")).string();
  std::ofstream(path) << ExportParameters(file, ExportTarget::kMjcf, ExportOptions{});
  MujocoRun run;
  run.drive = "axis";
  run.record = {{"axis", 0.0, 0.0, false}};
  run.max_step = 1e-6;     // 1e8 steps over the 100 s below
  run.max_seconds = 0.5;
  const std::vector<double> time = {0.0, 50.0, 100.0}, effort = {0.0, 0.5, 0.0};
  std::string message;
  try {
    SimulateMujoco(path, run, time, effort);
  } catch (const InputError& e) {
    message = e.what();
  }
  std::remove(path.c_str());
  CHECK_THAT(message, Catch::Contains("this model would take about") && Catch::Contains("more than 0.5 s"));
}
