#include "basis/Basis.h"

#include <fmt/format.h>

#include <vector>

namespace baker {

const char* colorSpaceName(ColorSpace space) { return space == ColorSpace::Rgb ? "RGB" : "YCoCg"; }

const char* channelName(ColorSpace space, int channel) {
  static const char* rgb[] = {"R", "G", "B"};
  static const char* ycocg[] = {"Y", "Co", "Cg"};
  return space == ColorSpace::Rgb ? rgb[channel] : ycocg[channel];
}

Eigen::Vector3f toColorSpace(ColorSpace space, const Eigen::Vector3f& c) {
  if (space == ColorSpace::Rgb) return c;
  return {0.25f * c.x() + 0.5f * c.y() + 0.25f * c.z(), 0.5f * c.x() - 0.5f * c.z(),
          -0.25f * c.x() + 0.5f * c.y() - 0.25f * c.z()};
}

Eigen::Vector3f toRgb(ColorSpace space, const Eigen::Vector3f& c) {
  if (space == ColorSpace::Rgb) return c;
  return {c.x() + c.y() - c.z(), c.x() + c.z(), c.x() - c.y() - c.z()};
}

std::string Basis::identity() const {
  std::string key = name();
  for (const auto& [parameter, value] : parameterSettings(parameters())) key += fmt::format("/{}={}", parameter, value);
  return key;
}

int Basis::coefficientOffset(int channel) const {
  int offset = 0;
  for (int c = 0; c < channel; ++c) offset += coefficientCount(c);
  return offset;
}

bool Basis::channelsShareFunctions() const { return &functions(0) == &functions(1) && &functions(1) == &functions(2); }

Eigen::Vector3f Basis::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  Eigen::Vector3f color;
  std::vector<double> values;
  for (int c = 0; c < 3; ++c) {
    const SphericalFunctions& f = functions(c);
    values.resize(f.count());
    f.evaluate(d, values.data());
    const float* coef = coefficients + coefficientOffset(c);
    double sum = 0.0;
    for (int i = 0; i < f.count(); ++i) sum += values[i] * coef[i];
    color[c] = float(sum);
  }
  return toRgb(colorSpace(), color);
}

}  // namespace baker
