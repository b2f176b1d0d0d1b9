// Logs whose position arrives in a device's status frames
// (workflow/status_frame_logs.h): each frame kept once, half a logger step
// before the row that first shows it, with the effort of the row before;
// the rows between frames keep their effort unmeasured; a log at every row
// is left alone.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "workflow/status_frame_logs.h"

namespace driveid {
namespace {

constexpr double kStep = 0.005;  // logger step h [s]
constexpr int kHold = 4;         // rows per status frame (20 ms frames)

// The position of a smooth motion measured in frames and repeated until
// the next (a frame changes at rows 0, 4, 8, ...), the effort at every row:
// a ramp (varying) or a step held from row 100.
AxisLog FramedLog(int rows, bool ramp) {
  AxisLog log;
  log.path = "framed.csv";
  for (int r = 0; r < rows; ++r) {
    log.time.push_back(r * kStep);
    log.force.push_back(ramp ? 0.001 * r : (r < 100 ? 0.0 : 1.0));
    const int frame_row = r - r % kHold;
    log.position.push_back(std::sin(3.0 * frame_row * kStep) + 0.2 * frame_row * kStep);
  }
  return log;
}

// The rule (RetimeStatusFrames): a frame is sent between the row before and
// the row that shows it (-h/2); a varying effort is centred on its row
// (+h/2), so the two cancel; a held step's timing does not move.
TEST_CASE("a position in status frames: each frame once, where the rule puts it, the rows between unmeasured") {
  for (const bool ramp : {true, false}) {
    const double shift = ramp ? 0.0 : -0.5 * kStep;
    const int rows = 2000;
    std::vector<AxisLog> logs{FramedLog(rows, ramp)};
    const AxisLog logged = logs[0];
    const StatusFrameRetiming retiming = RetimeStatusFrames(logs);
    INFO((ramp ? "a ramp of effort" : "a step of effort"));
    CHECK(retiming.held_logs == 1);
    CHECK(retiming.rows == static_cast<std::size_t>(rows));
    CHECK(retiming.frames == static_cast<std::size_t>(rows / kHold));
    CHECK(retiming.frame_period == Approx(kHold * kStep));
    CHECK(retiming.logger_step == Approx(kStep));
    const AxisLog& log = logs[0];
    REQUIRE(log.measured.size() == log.time.size());
    // The first frame, shown at the first row, has no row before it: it stays on it.
    REQUIRE(log.measured[0]);
    CHECK(log.time[0] == logged.time[0]);
    CHECK(log.position[0] == logged.position[0]);
    CHECK(log.force[0] == logged.force[0]);
    std::size_t checked = 1, wrong = 0;
    for (std::size_t k = 1; k < log.time.size(); ++k) {
      if (!log.measured[k]) continue;
      // The frame shown at row r: at t_r + shift, with row r's position and
      // the effort that acts there (row r - 1's when it sits before row r).
      const auto r = static_cast<std::size_t>(std::lround((log.time[k] - shift) / kStep));
      const double effort = shift < 0.0 ? logged.force[r > 0 ? r - 1 : 0] : logged.force[r];
      const bool right = r % kHold == 0 && std::abs(log.time[k] - (logged.time[r] + shift)) < 1e-9 &&
                         log.position[k] == logged.position[r] && log.force[k] == effort;
      wrong += right ? 0 : 1;
      ++checked;
    }
    CHECK(wrong == 0);
    CHECK(checked == retiming.frames);
    // Every logged row keeps its effort; a frame on a row's time replaces it.
    CHECK(log.time.size() == static_cast<std::size_t>(rows) + (ramp ? 0 : retiming.frames - 1));
    // The measured rows alone: the frames, in time order.
    const std::vector<AxisLog> measured = MeasuredRows(logs);
    REQUIRE(measured.size() == 1);
    CHECK(measured[0].time.size() == retiming.frames);
    for (std::size_t k = 1; k < measured[0].time.size(); ++k) CHECK(measured[0].time[k] > measured[0].time[k - 1]);
  }
}

TEST_CASE("a log measured at every row is left alone") {
  AxisLog log;
  log.path = "plain.csv";
  for (int r = 0; r < 1000; ++r) {
    log.time.push_back(r * kStep);
    log.force.push_back(0.001 * r);
    log.position.push_back(std::sin(3.0 * r * kStep));
  }
  std::vector<AxisLog> logs{log};
  const StatusFrameRetiming retiming = RetimeStatusFrames(logs);
  CHECK(retiming.held_logs == 0);
  CHECK(logs[0].time == log.time);
  CHECK(logs[0].position == log.position);
  CHECK(logs[0].force == log.force);
  CHECK(logs[0].measured.empty());
  CHECK(MeasuredRows(logs)[0].time == log.time);
}

}  // namespace
}  // namespace driveid
