// Fit-vs-measurement plots rendered with gnuplot (Debian gnuplot-nox):
// top panel measured and model per series, bottom panel the residuals.
// PNG or SVG by the output file's extension. The file appears atomically.
#pragma once

#include <string>
#include <vector>

namespace driveid {

struct PlotSeries {
  std::string title;            ///< e.g. the log's file name
  std::vector<double> time;     ///< [s]
  std::vector<double> measured;
  std::vector<double> model;
};

struct PlotLabels {
  std::string title;
  std::string y_label;  ///< e.g. "link torque [N m]"
};

/// One curve of a panel.
struct PlotLine {
  std::string title;
  std::vector<double> x;
  std::vector<double> y;
  bool points = false;  ///< thin dots in a light tint (measurements), under the next line (the model) in its full colour
  bool dots = false;    ///< coloured dots (scattered samples, e.g. residuals with gaps)
  bool grey = false;    ///< grey dots: samples shown but not counted (e.g. coherence below 0.5); no colour taken
};

/// One panel (stacked vertically, sharing the time axis).
struct PlotPanel {
  std::string title;
  std::string y_label;
  std::vector<PlotLine> lines;
  double y_min = 0.0, y_max = 0.0;  ///< fixed y range when y_max > y_min (e.g. a coherence's [0, 1])
  /// A panel with its own x axis (e.g. a step response under a Bode plot):
  /// its label and scale instead of the shared ones.
  std::string own_x_label{};
  bool own_log_x = false;
};

/// Renders stacked panels as the image `path` will hold (PNG or SVG by its
/// extension) and returns its bytes (the caller writes them with the other
/// outputs); the last panel gets the x label, `log_x` a logarithmic x axis
/// (a Bode plot). Throws OutputError if gnuplot is missing or fails.
std::string RenderPanels(const std::string& path, const std::vector<PlotPanel>& panels, const std::string& x_label,
                         bool log_x = false);

/// The gnuplot style of each line of a panel ("with points ... lc rgb '#...'").
/// Channels take colours in turn; a measured series (`points`) takes the
/// light tint of the colour its model line (the next line) takes in full, so
/// measured and model differ and each channel's pair belongs together.
std::vector<std::string> LineStyles(const std::vector<PlotLine>& lines);

/// True for a path ending in .png or .svg (case-insensitive).
bool IsSupportedPlotPath(const std::string& path);


/// The standard fit plot: measured (dots) and model (lines) of every series
/// in one panel, their residuals in a second.
std::vector<PlotPanel> MakeFitPanels(const std::vector<PlotSeries>& series, const PlotLabels& labels);

}  // namespace driveid
