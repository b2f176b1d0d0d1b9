// A test-only model added by following docs/adding-a-model.md, to prove it:
// a linear spring-damper with preload, F = k x + c v + f_0, fitted by
// inverse dynamics. Its struct, section, table, equation and the one line
// that registers its parameter-file section live here; its fit and tests
// in tests/models/test_spring_model_test.cc.
#pragma once

#include <optional>

#include "params/parameter_sections.h"
#include "models/parameter_table.h"

namespace driveid::testing {

/// The model's values (what the equation uses).
struct SpringParameters {
  double stiffness = 0.0;  ///< k [N/m]
  double damping = 0.0;    ///< c [N s/m]
  double preload = 0.0;    ///< f_0 [N]
};

/// The parameter file's section as written.
struct SpringSection {
  static constexpr const char* kSectionName = "test_spring";
  std::optional<double> stiffness, damping, preload;
};

inline const ParameterTable<SpringSection, SpringParameters>& SpringParameterTable() {
  using S = SpringSection;
  using P = SpringParameters;
  static const ParameterTable<S, P> table = {
      {Spec("k", "k", "N/m", "spring stiffness").Fit("spring").FreeByDefault(), &S::stiffness, &P::stiffness},
      {Spec("c", "c", "N s/m", "viscous damping").Fit("spring").FreeByDefault(), &S::damping, &P::damping},
      {Spec("f0", "f_0", "N", "preload").Unbounded().Fit("spring").FreeByDefault(), &S::preload, &P::preload},
  };
  return table;
}

/// F = k x + c v + f_0 [N].
inline double SpringForce(const SpringParameters& p, double x, double v) {
  return p.stiffness * x + p.damping * v + p.preload;
}

/// The one registration line: every parameter file may now hold the section.
inline const bool kSpringSectionRegistered =
    (RegisterParameterSection(MakeSection(SpringParameterTable, "test-only model: docs/adding-a-model.md")), true);

}  // namespace driveid::testing
