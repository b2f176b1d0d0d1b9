// Outputs of `drivetrain-fit frf` (docs/formats.md#frequency-response-csv):
// the response as CSV, the Bode plot (magnitude in dB and phase, coherence
// below; bins with coherence < 0.5 grey, the fitted model over them), the
// summary table and its JSON.
#pragma once

#include <string>
#include <vector>

#include "fit/frf/frf_analysis.h"
#include "report/json.h"
#include "report/plot.h"

namespace driveid {

/// frequency_hz, magnitude, phase_deg, coherence, magnitude_std, phase_std_deg
/// (and model_magnitude, model_phase_deg with a fit; the link's with a link).
std::string FormatFrfCsv(const FrfResult& result);

std::vector<PlotPanel> MakeBodePanels(const FrfResult& result);

/// Method, resonance and anti-resonance (read and fitted), band.
std::string FormatFrfSummary(const FrfResult& result);

Json FrfJson(const FrfResult& result);

}  // namespace driveid
