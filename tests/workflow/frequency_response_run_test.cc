// workflow/frequency_response_run.h and the other runs' edges: a measured
// response brought to Hz, |G| and radians against closed forms; quantity
// names and their refusal; a logged current made a torque with k_t (and
// refused by the log's name without one); the written file's sections; a
// synthetic log of a section the file lacks refused by the file's name.
#include "workflow/frequency_response_run.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "workflow/cdrive_simulation.h"
#include "workflow/synthetic_logs.h"

using namespace driveid;

TEST_CASE("measured response: rad/s, dB and degrees to Hz, |G| and radians") {
  MeasuredResponse m;
  m.frequency = {2.0 * M_PI, 20.0 * M_PI};
  m.magnitude = {20.0, -6.0};
  m.phase = {-90.0, 180.0};
  const MeasuredResponse si = MeasuredResponseInSi(m, {true, true, true});
  CHECK(si.frequency[0] == Approx(1.0));
  CHECK(si.frequency[1] == Approx(10.0));
  CHECK(si.magnitude[0] == Approx(10.0));
  CHECK(si.magnitude[1] == Approx(0.501187).epsilon(1e-5));  // 10^(-6/20)
  CHECK(si.phase[0] == Approx(-M_PI / 2.0));
  CHECK(si.phase[1] == Approx(M_PI));
  // Already in Hz, |G| and radians: untouched.
  const MeasuredResponse same = MeasuredResponseInSi(si, {false, false, false});
  CHECK(same.frequency == si.frequency);
  CHECK(same.magnitude == si.magnitude);
  CHECK(same.phase == si.phase);
}

TEST_CASE("response quantities by name; a signal's quantity from its name") {
  CHECK(ResponseQuantityFromName("position", "--output-is") == ResponseQuantity::kPosition);
  CHECK(ResponseQuantityFromName("rate", "--output-is") == ResponseQuantity::kRate);
  CHECK(ResponseQuantityFromName("acceleration", "--link-is") == ResponseQuantity::kAcceleration);
  CHECK_THROWS_AS(ResponseQuantityFromName("speed", "--link-is"), OptionError);
  CHECK(ResponseQuantityOfSignal("qd_motor") == "rate");
  CHECK(ResponseQuantityOfSignal("q_motor") == "position");
  CHECK(ResponseQuantityOfSignal("#5") == "");
}

TEST_CASE("frf signals from a log: current times k_t, reference and link taken when logged") {
  CsvLog log;
  log.path = "bench.csv";
  log.names = {"t", "i", "qd_motor", "reference", "q_link"};
  log.columns = {{0.0, 0.001}, {1.0, -2.0}, {3.0, 4.0}, {0.5, 0.6}, {7.0, 8.0}};
  const FrfSignals s = FrfSignalsFromLog(log, 0.25, true, true);
  CHECK(s.label == "bench.csv");
  CHECK(s.input == std::vector<double>{0.25, -0.5});
  CHECK(s.output == std::vector<double>{3.0, 4.0});
  CHECK(s.reference == std::vector<double>{0.5, 0.6});
  CHECK(s.link == std::vector<double>{7.0, 8.0});
  const FrfSignals open = FrfSignalsFromLog(log, 0.25, false, false);
  CHECK(open.reference.empty());
  CHECK(open.link.empty());
  CHECK_THROWS_WITH(FrfSignalsFromLog(log, 0.0, false, false),
                    Catch::StartsWith("bench.csv: a log of current i needs joint.k_t"));
  log.names[1] = "tau";
  CHECK(FrfSignalsFromLog(log, 0.0, false, false).input == std::vector<double>{1.0, -2.0});
}

TEST_CASE("frf's parameter file: the frf section always, the joint section with the estimates when fitted") {
  FrfResult result;
  result.rate = 1000.0;
  JointSection section;
  const ParameterFile without = FrfParameterFile(ParameterFile{}, section, result);
  CHECK(without.Find<JointSection>() == nullptr);
  CHECK(without.Find<FrequencyResponseSection>() != nullptr);
  TwoMassFitOutput fit;
  fit.params.stiffness = 21.5;
  result.fit = fit;
  const ParameterFile with = FrfParameterFile(ParameterFile{}, section, result);
  REQUIRE(with.Find<JointSection>() != nullptr);
  CHECK(with.Find<JointSection>()->stiffness.value_or(0.0) == 21.5);
  CHECK(with.Find<JointSection>()->gear_ratio.value_or(0.0) == 1.0);  // not given: 1
}

TEST_CASE("synthetic logs and the closed loop refuse a file without their section, by its name") {
  const ParameterFile empty;
  CHECK_THROWS_WITH(SyntheticStepLog(empty, "p.yaml", "reduced", StepExperiment{}, "cmd"),
                    "p.yaml: no 'drivetrain' section");
  CHECK_THROWS_WITH(SyntheticAxisLog(empty, "p.yaml", AxisExperiment{}, "", "cmd"), "p.yaml: no 'axis' section");
  CHECK_THROWS_WITH(SyntheticRobotLog(empty, "p.yaml", RobotExperiment{}, "cmd"), "p.yaml: no 'planar_robot' section");
  CHECK_THROWS_WITH(SyntheticJointLog(empty, "p.yaml", JointExperiment{}, "", false, "cmd"),
                    "p.yaml: no 'joint' section");
  CHECK_THROWS_WITH(SimulateCDrive(empty, "p.yaml", CDriveSimulationRequest{}, "cmd"), "p.yaml: no 'cdrive' section");
}
