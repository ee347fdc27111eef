#include "validate/AccuracyPlot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace baker {

std::string accuracyPlotSvg(const std::vector<AccuracyCurve>& curves, const std::string& title) {
  constexpr double kWidth = 720, kHeight = 480, kLeft = 80, kRight = 200, kTop = 40, kBottom = 60;
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
  double tMin = std::numeric_limits<double>::infinity(), tMax = 0, eMin = tMin, eMax = 0;
  for (const AccuracyCurve& c : curves)
    for (std::size_t i = 0; i < c.seconds.size(); ++i) {
      tMin = std::min(tMin, c.seconds[i]);
      tMax = std::max(tMax, c.seconds[i]);
      eMin = std::min(eMin, c.error[i]);
      eMax = std::max(eMax, c.error[i]);
    }
  if (!(tMax > 0) || !(eMax > 0)) return "<svg xmlns=\"http://www.w3.org/2000/svg\"/>\n";
  // Whole decades around the data, so the axes read as powers of ten.
  const double x0 = std::floor(std::log10(std::max(tMin, 1e-6))), x1 = std::max(x0 + 1, std::ceil(std::log10(tMax)));
  const double y0 = std::floor(std::log10(std::max(eMin, 1e-9))), y1 = std::max(y0 + 1, std::ceil(std::log10(eMax)));
  auto px = [&](double t) { return kLeft + (std::log10(t) - x0) / (x1 - x0) * (kWidth - kLeft - kRight); };
  auto py = [&](double e) { return kHeight - kBottom - (std::log10(e) - y0) / (y1 - y0) * (kHeight - kTop - kBottom); };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"24\" font-size=\"15\">{3}</text>\n",
      kWidth, kHeight, kLeft, title);
  for (double d = x0; d <= x1; ++d)
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#ddd\"/><text x=\"{0}\" y=\"{3}\" "
                       "text-anchor=\"middle\">1e{4}</text>\n",
                       px(std::pow(10, d)), kTop, kHeight - kBottom, kHeight - kBottom + 18, int(d));
  for (double d = y0; d <= y1; ++d)
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"#ddd\"/><text x=\"{3}\" y=\"{4}\" "
                       "text-anchor=\"end\">1e{5}</text>\n",
                       kLeft, py(std::pow(10, d)), kWidth - kRight, kLeft - 6, py(std::pow(10, d)) + 4, int(d));
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">bake time (s)</text>\n",
                     (kLeft + kWidth - kRight) / 2, kHeight - 18);
  svg += fmt::format("<text transform=\"translate(20 {}) rotate(-90)\" text-anchor=\"middle\">relative RMSE of "
                     "irradiance</text>\n",
                     (kTop + kHeight - kBottom) / 2);
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const AccuracyCurve& curve = curves[c];
    const char* colour = colours[c % 8];
    std::string points;
    for (std::size_t i = 0; i < curve.seconds.size(); ++i)
      points += fmt::format("{:.1f},{:.1f} ", px(curve.seconds[i]), py(curve.error[i]));
    svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>\n", points, colour);
    for (std::size_t i = 0; i < curve.seconds.size(); ++i)
      svg += fmt::format("<circle cx=\"{0:.1f}\" cy=\"{1:.1f}\" r=\"3\" fill=\"{2}\"/><text x=\"{3:.1f}\" y=\"{4:.1f}\" "
                         "font-size=\"10\" fill=\"{2}\">{5}</text>\n",
                         px(curve.seconds[i]), py(curve.error[i]), colour, px(curve.seconds[i]) + 4,
                         py(curve.error[i]) - 4, curve.pointLabels[i]);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" stroke-width=\"2\"/><text "
                       "x=\"{4}\" y=\"{5}\">{6}</text>\n",
                       kWidth - kRight + 15, kTop + 20 * c + 10, kWidth - kRight + 40, colour, kWidth - kRight + 46,
                       kTop + 20 * c + 14, curve.label);
  }
  return svg + "</svg>\n";
}

}  // namespace baker
