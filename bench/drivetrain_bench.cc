// Benchmark (not a test): CSV parse throughput and step-fit time vs number of
// samples. Prints a Markdown table. Usage: drivetrain_bench [repetitions]
//
// Data: the paper's drive train (docs/models.md#drive-train), reduced model, -0.8 N m step at
// 20 ms in a 0.2 s log, noise 0.1 N m; the fit starts 2-3x off with
// --free d_g,Theta_motor,tau_c,offset. More samples = a higher rate.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fit/axis/axis_fit.h"
#include "fit/cdrive/cdrive_fit.h"
#include "fit/robot/robot_fit.h"
#include "fit/step/step_fit.h"
#include "logs/log_input.h"
#include "sim/axis_experiment.h"
#include "sim/cdrive_closed_loop.h"
#include "sim/robot_experiment.h"
#include "sim/step_experiment.h"
#include "support/paper000.h"
#include "support/paper001.h"

using namespace driveid;

namespace {
double Seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;

  // CSV parse: a 1,000,000-row step log (about 33 MB) parsed from memory.
  StepExperiment big;
  big.rate = 5e6;
  big.noise = 0.1;
  const StepLog big_log = SimulateStepExperiment(testing_support::PaperDriveTrain(), big);
  const std::string text = FormatStepLog(big_log, {"benchmark"});
  double best = 1e30;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const CsvLog log = ParseCsvLog("bench.csv", text, {"t", "tau_motor", "tau_link"});
    best = std::min(best, Seconds(std::chrono::steady_clock::now() - start));
    if (log.rows() != big_log.time.size()) return 1;
  }
  const double megabytes = static_cast<double>(text.size()) / 1e6;
  std::printf("| CSV parse | %zu rows, %.1f MB | %.1f ms | %.0f MB/s |\n", big_log.time.size(), megabytes, best * 1e3,
              megabytes / best);

  std::printf("\n| samples | model | free | fit time (best of %d) | per 1000 samples | iterations | d_g error |\n",
              repetitions);
  std::printf("|---:|---|---|---:|---:|---:|---:|\n");
  for (const char* model_name : {"reduced", "full"}) {
    const bool full = std::string(model_name) == "full";
    for (int samples : {200, 1000, 5000, 20000, 100000}) {
      StepExperiment e;
      e.model = full ? DriveTrainModel::kFull : DriveTrainModel::kReduced;
      e.rate = (samples - 1) / e.duration;
      e.noise = 0.1;
      e.offset = 0.5;
      e.seed = 7;
      StepLog log = SimulateStepExperiment(testing_support::PaperDriveTrain(), e);
      log.path = "bench";
      DriveTrainParameters start = testing_support::PaperDriveTrain();
      start.motor_inertia *= 2.5;
      start.viscous_friction /= 3.0;
      start.coulomb_friction *= 2.0;
      StepFitOptions options;
      options.model = e.model;
      options.free = {"d_g", "Theta_motor", "tau_c", "offset"};
      double fastest = 1e30;
      StepFitOutput out;
      for (int r = 0; r < repetitions; ++r) {
        const auto begin = std::chrono::steady_clock::now();
        out = FitStepResponses({log}, start, options);
        fastest = std::min(fastest, Seconds(std::chrono::steady_clock::now() - begin));
      }
      std::printf("| %d | %s | 4 | %.2f ms | %.3f ms | %d | %+.2f %% |\n", samples, model_name, fastest * 1e3,
                  fastest * 1e6 / samples, out.fit.iterations, 100.0 * (out.params.viscous_friction / 0.016 - 1.0));
    }
  }

  // The other fits vs samples (library time, best of the repetitions).
  auto time_best = [&](auto&& fit) {
    double fastest = 1e30;
    for (int r = 0; r < repetitions; ++r) {
      const auto begin = std::chrono::steady_clock::now();
      fit();
      fastest = std::min(fastest, Seconds(std::chrono::steady_clock::now() - begin));
    }
    return fastest * 1e3;
  };
  std::printf("\n| fit | samples | time (best of %d) | time per 1000 samples |\n|---|---:|---:|---:|\n", repetitions);
  const AxisParameters axis_truth{0.05, 0.2, 1.0, 0.3};
  for (double duration : {2.5, 10.0, 25.0, 100.0}) {
    AxisExperiment e;
    e.noise = 0.05;
    e.duration = duration;
    const AxisLog log = SimulateAxisExperiment(axis_truth, e);
    const double ms = time_best([&] { FitAxis({log}, AxisSection{0.1, 0.5, 2.0, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}}, {}); });
    std::printf("| axis (IDIM-LS) | %zu | %.2f ms | %.3f ms |\n", log.time.size(), ms, ms * 1000.0 / static_cast<double>(log.time.size()));
  }
  const CDriveParameters cdrive = testing_support::TableOneCDrive();
  CDriveControlSettings control;
  control.law = ControlLaw::kPD;
  for (int cycles : {1, 2, 4, 8}) {
    std::vector<CDriveLog> logs;
    std::size_t samples = 0;
    for (const char* program : {"translation", "rotation", "helical"}) {
      ClosedLoopOptions options;
      options.program = TableTwoProgram(program, 4.0);
      options.cycles = cycles;
      options.torque_noise = 0.01;
      logs.push_back(SimulateClosedLoop(cdrive, control, options).log);
      samples += logs.back().time.size();
    }
    const double ms = time_best([&] { FitCDriveFriction(logs, MakeSection(CDriveParameterTable(), cdrive), {}); });
    std::printf("| C-drive friction | %zu | %.2f ms | %.3f ms |\n", samples, ms, ms * 1000.0 / static_cast<double>(samples));
  }
  const PlanarRobotParameters robot;
  PlanarRobotParameters robot_start = robot;
  robot_start.output_inertia = 1.0;
  robot_start.center_mass = 1.0;
  robot_start.viscous_friction = 0.001;
  for (int loops : {3, 12, 48}) {
    RobotExperiment e;
    e.loops = loops;
    e.current_noise = 0.02;
    const RobotLog log = SimulateRobotExperiment(robot, e);
    const double ms = time_best([&] { FitRobot({log}, robot_start, {}); });
    std::printf("| robot | %zu | %.2f ms | %.3f ms |\n", log.time.size(), ms, ms * 1000.0 / static_cast<double>(log.time.size()));
  }
  return 0;
}
