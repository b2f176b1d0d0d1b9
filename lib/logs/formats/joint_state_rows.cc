#include "logs/formats/joint_state_rows.h"

#include <algorithm>
#include <limits>

namespace driveid {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

}  // namespace

JointStateRows::JointStateRows(std::vector<std::string> keep, bool all) : kept(std::move(keep)), all_(all && kept.empty()) {
  values.resize(kept.size());
}

std::size_t JointStateRows::Slot(const std::string& joint) {
  const auto found = std::find(kept.begin(), kept.end(), joint);
  if (found != kept.end()) return static_cast<std::size_t>(found - kept.begin());
  if (!all_) return kNone;
  kept.push_back(joint);
  values.emplace_back();
  for (auto& v : values.back()) v.assign(stamp_ns.size(), std::numeric_limits<double>::quiet_NaN());
  return kept.size() - 1;
}

void JointStateRows::Add(const JointStateMessage& m) {
  ++messages_;
  const std::array<const std::vector<double>*, 3> arrays = {&m.position, &m.velocity, &m.effort};
  for (std::size_t f = 0; f < 3; ++f) filled_[f] += !arrays[f]->empty();
  if (m.name != last_names_) {
    last_names_ = m.name;
    last_seen_.clear();
    last_kept_.clear();
    for (const auto& n : m.name) {
      auto found = std::find_if(seen_.begin(), seen_.end(), [&](const auto& p) { return p.first == n; });
      if (found == seen_.end()) {
        seen_.emplace_back(n, 0);
        found = seen_.end() - 1;
      }
      last_seen_.push_back(static_cast<std::size_t>(found - seen_.begin()));
      last_kept_.push_back(Slot(n));
    }
  }
  // A name given twice in one message counts once.
  for (std::size_t i = 0; i < last_seen_.size(); ++i) {
    if (std::find(last_seen_.begin(), last_seen_.begin() + static_cast<std::ptrdiff_t>(i), last_seen_[i]) ==
        last_seen_.begin() + static_cast<std::ptrdiff_t>(i)) {
      ++seen_[last_seen_[i]].second;
    }
  }
  if (kept.empty()) return;
  // Where each kept joint is in this message (its first occurrence).
  std::vector<std::size_t>& at = at_;
  at.assign(kept.size(), kNone);
  for (std::size_t i = last_kept_.size(); i-- > 0;) {
    if (last_kept_[i] != kNone) at[last_kept_[i]] = i;
  }
  if (!all_ && std::count(at.begin(), at.end(), kNone) > 0) {
    ++without_;
    return;
  }
  std::uint8_t flag = 0;
  for (std::size_t f = 0; f < 3; ++f) flag |= static_cast<std::uint8_t>((arrays[f]->size() == m.name.size()) << f);
  stamp_ns.push_back(m.stamp_ns);
  receive_ns.push_back(m.receive_ns);
  flags.push_back(flag);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    for (std::size_t f = 0; f < 3; ++f) {
      const bool has = at[k] != kNone && (flag >> f & 1) != 0;
      values[k][f].push_back(has ? (*arrays[f])[at[k]] : std::numeric_limits<double>::quiet_NaN());
    }
  }
}

}  // namespace driveid
