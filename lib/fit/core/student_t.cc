#include "fit/core/student_t.h"

#include <limits>

#include <boost/math/distributions/students_t.hpp>

namespace driveid {

double StudentT975(int dof) {
  if (dof < 1) return std::numeric_limits<double>::infinity();
  const boost::math::students_t distribution(static_cast<double>(dof));
  return boost::math::quantile(boost::math::complement(distribution, 0.025));
}

}  // namespace driveid
