// "Do not evaluate this point twice", the one memo of the fit core: the
// last point a model was evaluated at, compared bit for bit (a point that
// differs in the last bit is another point), and what that evaluation left:
// whether it succeeded and whether it has the Jacobian. Ceres's bounded
// Levenberg-Marquardt asks for each new point three times (candidate with
// Jacobian, its cost, its Jacobian once accepted); the statistics evaluate
// the optimum once more; a large problem asks for its rows in chunks. The
// cost (fit/scaled_cost) keeps residuals and Jacobian behind one; the step
// model (fit/step/step_fit.cc) its simulation, whole or streamed.
#pragma once

#include <cstring>
#include <vector>

namespace driveid {

class PointMemo {
 public:
  /// Whether the memo holds the point (a, then b: the shared and a block's
  /// own parameters; either may be empty).
  bool Holds(const double* a, std::size_t na, const double* b = nullptr, std::size_t nb = 0) const {
    return valid_ && point_.size() == na + nb && (na == 0 || std::memcmp(point_.data(), a, na * sizeof(double)) == 0) &&
           (nb == 0 || std::memcmp(point_.data() + na, b, nb * sizeof(double)) == 0);
  }
  /// Remembers the point (what its evaluation left is set by the caller).
  void Remember(const double* a, std::size_t na, const double* b = nullptr, std::size_t nb = 0) {
    point_.assign(a, a + na);
    if (nb > 0) point_.insert(point_.end(), b, b + nb);
    valid_ = true;
  }
  /// Holds no point (an evaluation under way, or the model released).
  void Forget() { valid_ = false; }
  bool valid() const { return valid_; }

  bool succeeded = false;     ///< the evaluation at the point succeeded
  bool with_jacobian = false;  ///< it computed (and the holder keeps) the Jacobian

 private:
  std::vector<double> point_;
  bool valid_ = false;
};

}  // namespace driveid
