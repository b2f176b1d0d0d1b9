// sim/step_experiment.h: the step log holds the commanded step (before and
// after its time), a noise-free log plus its offset is the offset-free log
// shifted, the same seed gives the same noise, and settings outside their
// bounds are refused by name.
#include "sim/step_experiment.h"

#include <cstdlib>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "params/parameter_file.h"

using namespace driveid;

TEST_CASE("step experiment: the step as commanded, the offset a shift, the seed reproducible, refusals") {
  const char* source = std::getenv("DRIVEID_SOURCE_DIR");
  const ParameterFile file = ReadParameterFile(std::string(source ? source : ".") + "/data/paper000.yaml");
  const DriveTrainParameters p = MakeDriveTrainParameters(*file.Find<DriveTrainSection>());
  StepExperiment e;
  e.duration = 0.1;
  const StepLog clean = SimulateStepExperiment(p, e);
  REQUIRE(clean.time.size() == 101);
  for (std::size_t k = 0; k < clean.time.size(); ++k) {
    CHECK(clean.motor_torque[k] == (clean.time[k] < e.step_time ? 0.0 : e.step_torque));
  }
  e.offset = 0.25;
  const StepLog shifted = SimulateStepExperiment(p, e);
  for (std::size_t k = 0; k < clean.time.size(); ++k) {
    CHECK(shifted.link_torque[k] == Approx(clean.link_torque[k] + 0.25).margin(1e-12));
  }
  e.noise = 0.1;
  const StepLog noisy = SimulateStepExperiment(p, e);
  CHECK(SimulateStepExperiment(p, e).link_torque == noisy.link_torque);
  e.seed = 2;
  CHECK(SimulateStepExperiment(p, e).link_torque != noisy.link_torque);
  e.step_time = e.duration;
  CHECK_THROWS_AS(ValidateStepExperiment(e), OptionError);
  e.step_time = 0.02;
  e.noise = -1.0;
  CHECK_THROWS_WITH(ValidateStepExperiment(e), Catch::StartsWith("‹noise› = -1"));
}
