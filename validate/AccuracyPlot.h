#pragma once
#include <string>
#include <vector>

namespace baker {

// One curve of an error-against-time plot: a basis (and bounce count), one point per ray count.
struct AccuracyCurve {
  std::string label;
  std::vector<double> seconds;
  std::vector<double> error;
  std::vector<std::string> pointLabels;
};

// A self-contained SVG: log-log axes of relative error against bake time, a coloured polyline
// per curve with its points labelled, a legend.
std::string accuracyPlotSvg(const std::vector<AccuracyCurve>& curves, const std::string& title);

}  // namespace baker
