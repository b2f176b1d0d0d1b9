#include "fit/joint/joint_oe_segments.h"

#include <algorithm>
#include <cmath>

namespace driveid {
namespace {

// Samples over which a start rate is taken when it is not logged.
constexpr std::size_t kStartRateSamples = 10;

// A segment's start rate: the logged rate, else the slope of a line through
// its first samples; `moving` when that slope is more than 5 of its
// standard errors from 0 (a log that starts at rest leaves a sticking
// motor's start rate at 0: nothing in the log could determine it).
struct StartRate {
  double value = 0.0;
  bool moving = false;
};
StartRate CalcStartRate(const std::vector<double>& time, const std::vector<double>& angle,
                        const std::vector<double>& rate, std::size_t begin, std::size_t end) {
  const std::size_t m = std::min(kStartRateSamples, end - begin);
  double mean_t = 0.0, mean_q = 0.0;
  for (std::size_t k = begin; k < begin + m; ++k) {
    mean_t += time[k] / static_cast<double>(m);
    mean_q += angle[k] / static_cast<double>(m);
  }
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = begin; k < begin + m; ++k) {
    sxx += (time[k] - mean_t) * (time[k] - mean_t);
    sxy += (time[k] - mean_t) * (angle[k] - mean_q);
  }
  StartRate out;
  if (!(sxx > 0.0) || m < 3) return out;
  const double slope = sxy / sxx;
  double scatter = 0.0;
  for (std::size_t k = begin; k < begin + m; ++k) {
    const double r = angle[k] - mean_q - slope * (time[k] - mean_t);
    scatter += r * r;
  }
  const double standard_error = std::sqrt(scatter / static_cast<double>(m - 2) / sxx);
  out.value = rate.empty() ? slope : rate[begin];
  out.moving = std::abs(slope) > 5.0 * standard_error;
  return out;
}

}  // namespace

double LongestDuration(const std::vector<JointLog>& logs) {
  double longest = 0.0;
  for (const auto& log : logs) {
    if (log.time.size() > 1) longest = std::max(longest, log.time.back() - log.time.front());
  }
  return longest;
}

double AutoSegmentSeconds(const std::vector<JointLog>& logs, const JointParameters& p) {
  const double omega_squared = p.stiffness * (1.0 / p.motor_inertia + 1.0 / p.link_inertia);
  if (!(omega_squared > 0.0) || !std::isfinite(omega_squared)) return HUGE_VAL;
  return std::max(kSegmentResonancePeriods * 2.0 * M_PI / std::sqrt(omega_squared),
                  LongestDuration(logs) / kMaxAutoSegments);
}

std::size_t SegmentSamples(const JointLog& log, double seconds) {
  const std::size_t samples = log.time.size();
  if (!(seconds > 0.0) || std::isinf(seconds) || samples < 2) return samples;
  const double step = (log.time.back() - log.time.front()) / static_cast<double>(samples - 1);
  if (!(step > 0.0) || !std::isfinite(seconds / step)) return samples;
  const double wanted = std::ceil(seconds / step);
  if (wanted >= static_cast<double>(samples)) return samples;
  return std::max(kMinSegmentSamples, static_cast<std::size_t>(wanted));
}

std::vector<OeSegment> SplitLog(const JointLog& log, const std::vector<double>& torque, double n,
                                std::size_t samples) {
  const std::size_t total = log.time.size();
  const std::size_t count = std::max<std::size_t>(1, total / std::max<std::size_t>(samples, 1));
  std::vector<OeSegment> segments(count);
  for (std::size_t s = 0; s < count; ++s) {
    OeSegment& g = segments[s];
    g.begin = s * total / count;
    g.end = (s + 1) * total / count;
    g.time.assign(log.time.begin() + static_cast<std::ptrdiff_t>(g.begin),
                  log.time.begin() + static_cast<std::ptrdiff_t>(g.end));
    g.torque.assign(torque.begin() + static_cast<std::ptrdiff_t>(g.begin),
                    torque.begin() + static_cast<std::ptrdiff_t>(g.end));
    const StartRate motor = CalcStartRate(log.time, log.motor_position, log.motor_rate, g.begin, g.end);
    const StartRate link = CalcStartRate(log.time, log.link_position, log.link_rate, g.begin, g.end);
    g.x0 = {log.motor_position[g.begin] / n, motor.moving ? motor.value / n : 0.0, log.link_position[g.begin],
            link.value};
    g.motor_moving = motor.moving;
  }
  return segments;
}

}  // namespace driveid
