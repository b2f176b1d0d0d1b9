// The C-drive plant (28), M psi'' + C psi' + phi_c = tau, with Coulomb
// friction that truly sticks at its three contacts (models/cdrive.h):
// motor L (v = psi_L', limit delta, g = (1, 0)), motor R (psi_R', delta,
// (0, 1)) and the collar on the screws (psi_L' - psi_R', eta, (1, -1)).
//
// Modes: each contact slides (f = -+limit) or sticks. With two degrees of
// freedom the possible stuck sets are {}, {L}, {R}, {collar} and all three.
// A single stuck contact k adds the constraint g_k' psi'' = 0 with the force
//   f_k = g_k' M^-1 F / (g_k' M^-1 g_k),  F = tau - C psi' - sum_sliding limit_i s_i g_i,
// and holds while |f_k| <= limit_k. All stuck: psi' = psi'' = 0 while some
// f with |f_i| <= limit_i balances tau (f_collar in
// [tau_L - delta, tau_L + delta] n [-tau_R - delta, -tau_R + delta] n [-eta, eta]).
// CVODES integrates the smooth field of the current mode; roots end it:
// a sliding contact's velocity crossing zero (that contact is then at rest:
// its velocity is projected out, since the root's placement to ~100 ulp of t
// leaves more than the zero threshold late in long runs), or a stuck
// contact's force reaching its limit. The next mode is the most-stuck candidate that is
// consistent (forces within limits, sliding directions agreeing with the
// accelerations), found by enumeration. The torque is held over each call.
// Documented in docs/models.md#c-drive.
#pragma once

#include <array>
#include <memory>

#include "models/cdrive.h"

namespace driveid {

struct CDrivePlantState {
  Vector2 angle = Vector2::Zero();  ///< psi [rad]
  Vector2 rate = Vector2::Zero();   ///< psi' [rad/s]
};

class CDrivePlant {
 public:
  /// Needs I_h, I_c, m and the four dissipation parameters of `params`.
  explicit CDrivePlant(const CDriveParameters& params);
  ~CDrivePlant();
  CDrivePlant(const CDrivePlant&) = delete;
  CDrivePlant& operator=(const CDrivePlant&) = delete;

  void Reset(const CDrivePlantState& state);
  /// Integrates from time `from` to `to` with the torque held. Throws
  /// IdentificationError if the integrator fails.
  void Advance(double from, double to, const Vector2& torque);

  const CDrivePlantState& state() const;
  /// Stuck contacts (L, R, collar) after the last Advance.
  std::array<bool, 3> stuck() const;
  int switch_count() const;

 private:
  class System;
  std::unique_ptr<System> system_;
};

}  // namespace driveid
