#include "workflow/excitation_design.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "models/missing_values.h"
#include "report/design_report.h"
#include "report/joint_design_report.h"

namespace driveid {

bool ExcitationDesignRequest::IsValid(std::string* error) const {
  return OptionCheck(error).Require(band.empty() || band.size() == 2, "‹band›: LO,HI or nothing");
}

ExcitationDesignRun DesignAxisRun(const ParameterFile& file, AxisDesignOptions design, const ExcitationDesignRequest& r) {
  RequireValid(r);
  const AxisSection* section = file.Find<AxisSection>();
  if (!section) throw InputError(fmt::format("{}: no 'axis' section", r.params_path));
  RequireModelValues(AxisParameterTable(), *section, r.params_path, "axis", "the design", AxisTermsZeroUnlessGiven(*section));
  const AxisParameters prior = MakeModelParameters(AxisParameterTable(), *section, AxisParameters{}, "axis");
  if (r.band.size() == 2) {
    design.band_low = r.band[0];
    design.band_high = r.band[1];
  }
  design.targets = r.targets;
  // The torque noise: given, else the prior's inverse-dynamics residuals.
  if (!(design.noise > 0.0)) design.noise = NoiseFromIdimResiduals(file.fit_rmse, file.fit_inflation);
  if (!(design.noise > 0.0)) {
    throw OptionError(fmt::format("‹noise›: {} has no inverse-dynamics fit residual to take the torque noise from; "
                                  "give ‹noise›",
                                  r.params_path));
  }
  const AxisDesign d = DesignAxisExcitation(prior, design);
  ExcitationDesignRun out;
  if (r.csv) {
    std::vector<std::string> comments = {"axis reference (docs/formats.md#references) designed by: " + r.command_line};
    for (std::size_t j = 0; j < d.free.size(); ++j) {
      comments.push_back(fmt::format("predicted std {}: {:.6g}", d.free[j], d.designed.predicted_std[j]));
    }
    std::string lines;
    for (double f : d.designed.reference.LineFrequencies()) lines += fmt::format(" {:.6g}", f);
    comments.push_back(fmt::format("excited lines [Hz]:{}", lines));
    out.csv = FormatAxisReference(DesignedReference(d, prior, design.rate, design.duration), comments);
  }
  if (r.plot) out.panels = AxisDesignPanels(d, prior, design.rate);
  out.printed = r.json ? DumpJson(AxisDesignJson(d)) : FormatAxisDesign(d, section->linear);
  return out;
}

ExcitationDesignRun DesignJointRun(const ParameterFile& file, JointDesignOptions design, const ExcitationDesignRequest& r) {
  RequireValid(r);
  const JointSection* section = file.Find<JointSection>();
  if (!section) throw InputError(fmt::format("{}: no 'joint' section", r.params_path));
  if (!section->gear_ratio) throw InputError(fmt::format("{}: joint.gear_ratio is needed", r.params_path));
  const JointParameters prior = ModelValuesOr(JointParameterTable(), *section, 0.0);
  if (r.band.size() == 2) {
    design.band_low = r.band[0];
    design.band_high = r.band[1];
  }
  design.targets = r.targets;
  const JointDesign d = DesignJointExcitation(prior, *section->gear_ratio, design);
  ExcitationDesignRun out;
  if (r.csv) {
    std::vector<std::string> comments = {"joint excitation (docs/formats.md#references) designed by: " + r.command_line};
    for (std::size_t j = 0; j < d.free.size(); ++j) {
      comments.push_back(fmt::format("predicted std {}: {:.6g}", d.free[j], d.designed.predicted_std[j]));
    }
    comments.push_back(fmt::format("rms torque {:.6g} N m, period {:.6g} s", d.designed.rms, d.period));
    out.csv = FormatTorqueReference(DesignedExcitation(d, design.rate, design.duration), comments);
  }
  if (r.plot) out.panels = JointDesignPanels(d, design.rate);
  out.printed = r.json ? DumpJson(JointDesignJson(d)) : FormatJointDesign(d);
  return out;
}

}  // namespace driveid
