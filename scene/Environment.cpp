#include "scene/Environment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/Error.h"

namespace baker {
namespace {

constexpr double kPi = M_PI;

// cos θ at the top edge of lat-long row `row` of `height` (θ = 0 at +Y).
double cosEdge(int row, int height) { return std::cos(kPi * row / height); }

}  // namespace

Environment Environment::constant(const Eigen::Vector3f& radiance) {
  Environment env;
  env.kind_ = Kind::Constant;
  env.constant_ = radiance;
  return env;
}

Environment Environment::latLong(int width, int height, std::vector<float> rgb, float intensity,
                                 float rotationDegrees, std::string source) {
  if (width <= 0 || height <= 0 || rgb.size() != std::size_t(width) * height * 3)
    throw std::invalid_argument("Environment: texels do not match the image size");
  Environment env;
  env.kind_ = Kind::Map;
  env.source_ = std::move(source);
  env.width_ = width;
  env.height_ = height;
  env.intensity_ = intensity;
  env.rotationDegrees_ = rotationDegrees;
  const double radians = double(rotationDegrees) * kPi / 180.0;
  env.cosRotation_ = float(std::cos(radians));
  env.sinRotation_ = float(std::sin(radians));
  for (std::size_t t = 0; t < rgb.size() / 3; ++t) {
    float* texel = &rgb[3 * t];
    if (!(std::isfinite(texel[0]) && std::isfinite(texel[1]) && std::isfinite(texel[2]) && texel[0] >= 0.0f &&
          texel[1] >= 0.0f && texel[2] >= 0.0f)) {
      ++env.sanitized_;
      std::fill_n(texel, 3, 0.0f);
    }
    for (int c = 0; c < 3; ++c) texel[c] *= intensity;
    if (!Eigen::Vector3f::Map(texel).allFinite())
      throw SettingError("env_intensity", fmt::format("{} takes texel ({}, {}) of {} beyond single precision", intensity,
                                                      t % width, t / width, env.source_));
  }
  env.rgb_ = std::move(rgb);

  // Weight = luminance × the texel's exact solid angle (2π/W)(cos θtop − cos θbottom): the
  // probability of a texel is then its share of the luminance integral, and the density
  // within it (uniform in φ and cos θ) is luminance / integral everywhere.
  std::vector<double> weights(std::size_t(width) * height);
  for (int j = 0; j < height; ++j) {
    const double solidAngle = env.texelSolidAngle(j);
    for (int i = 0; i < width; ++i) {
      const std::size_t t = std::size_t(j) * width + i;
      weights[t] = double(luminance(Eigen::Vector3f::Map(&env.rgb_[3 * t]))) * solidAngle;
    }
  }
  auto table = std::make_shared<PiecewiseConstant2D>(width, height, weights);
  env.luminanceIntegral_ = table->total();
  if (env.luminanceIntegral_ > 0.0) env.table_ = std::move(table);
  return env;
}

std::string Environment::describe() const {
  switch (kind_) {
    case Kind::None: return "none";
    case Kind::Constant: return fmt::format("constant sky {},{},{}", constant_.x(), constant_.y(), constant_.z());
    case Kind::Map: break;
  }
  return fmt::format("map {} ({} × {}, intensity {}, rotated {}°)", source_, width_, height_, intensity_,
                     rotationDegrees_);
}

Eigen::Vector3f Environment::toMap(const Eigen::Vector3f& w) const {
  // Rotating the map by +α means looking it up with the direction turned by −α.
  return {cosRotation_ * w.x() - sinRotation_ * w.z(), w.y(), sinRotation_ * w.x() + cosRotation_ * w.z()};
}

Eigen::Vector3f Environment::toWorld(const Eigen::Vector3f& m) const {
  return {cosRotation_ * m.x() + sinRotation_ * m.z(), m.y(), -sinRotation_ * m.x() + cosRotation_ * m.z()};
}

Eigen::Vector2i Environment::texelOf(const Eigen::Vector3f& direction) const {
  const Eigen::Vector3f d = toMap(direction);
  const double u = 0.5 + std::atan2(double(d.z()), double(d.x())) / (2.0 * kPi);
  const double v = std::acos(std::clamp(double(d.y()), -1.0, 1.0)) / kPi;
  return {std::clamp(int(std::floor(u * width_)), 0, width_ - 1), std::clamp(int(std::floor(v * height_)), 0, height_ - 1)};
}

Eigen::Vector3d Environment::texelCentre(int column, int row) const {
  return directionAt((column + 0.5) / width_, (row + 0.5) / height_);
}

Eigen::Vector3d Environment::directionAt(double u, double v) const {
  const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
  const Eigen::Vector3d m(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  const double c = double(cosRotation_), s = double(sinRotation_);
  return {c * m.x() + s * m.z(), m.y(), -s * m.x() + c * m.z()};
}

double Environment::texelSolidAngle(int row) const {
  return 2.0 * kPi / width_ * (cosEdge(row, height_) - cosEdge(row + 1, height_));
}

Eigen::Vector3f Environment::radiance(const Eigen::Vector3f& direction) const {
  switch (kind_) {
    case Kind::None: return Eigen::Vector3f::Zero();
    case Kind::Constant: return constant_;
    case Kind::Map: break;
  }
  const Eigen::Vector2i t = texelOf(direction);
  return Eigen::Vector3f::Map(&rgb_[3 * (std::size_t(t.y()) * width_ + t.x())]);
}

Environment::Sample Environment::sample(float xi1, float xi2) const {
  Sample s;
  if (kind_ == Kind::Constant) {
    if (luminance(constant_) <= 0.0f) return s;
    const float cosTheta = 1.0f - 2.0f * xi1, phi = 2.0f * float(kPi) * xi2;
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    s.direction = {sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi)};
    s.radiance = constant_;
    s.pdf = float(1.0 / (4.0 * kPi));
    return s;
  }
  if (kind_ != Kind::Map || !table_) return s;
  int i = 0, j = 0;
  double withinColumn = 0.0, withinRow = 0.0;
  table_->sample(xi1, xi2, &i, &j, &withinColumn, &withinRow);
  const double phi = 2.0 * kPi * ((i + withinColumn) / width_ - 0.5);
  const double cosTop = cosEdge(j, height_), cosBottom = cosEdge(j + 1, height_);
  const double cosTheta = cosTop + withinRow * (cosBottom - cosTop);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  s.direction = toWorld(Eigen::Vector3f(float(sinTheta * std::cos(phi)), float(cosTheta), float(sinTheta * std::sin(phi))));
  s.radiance = Eigen::Vector3f::Map(&rgb_[3 * (std::size_t(j) * width_ + i)]);
  s.pdf = float(luminance(s.radiance) / luminanceIntegral_);
  return s;
}

float Environment::pdf(const Eigen::Vector3f& direction) const {
  if (kind_ == Kind::Constant) return luminance(constant_) > 0.0f ? float(1.0 / (4.0 * kPi)) : 0.0f;
  if (kind_ != Kind::Map || !table_) return 0.0f;
  return float(luminance(radiance(direction)) / luminanceIntegral_);
}

}  // namespace baker
