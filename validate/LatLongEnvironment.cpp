#include "validate/LatLongEnvironment.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "common/Error.h"
#include "images/RgbImage.h"

namespace baker {

LatLongEnvironment::LatLongEnvironment(int width, int height, Eigen::MatrixX3d radiance)
    : width_(width), height_(height), radiance_(std::move(radiance)) {
  if (width <= 0 || height <= 0 || radiance_.rows() != Eigen::Index(width) * height)
    throw std::invalid_argument("lat-long environment: radiance does not match the image size");
}

LatLongEnvironment LatLongEnvironment::load(const std::string& path) {
  const RgbImage image = readRgbImage(path);
  Eigen::MatrixX3d radiance(Eigen::Index(image.width) * image.height, 3);
  static const char* channel[] = {"R", "G", "B"};
  for (int row = 0; row < image.height; ++row)
    for (int column = 0; column < image.width; ++column)
      for (int c = 0; c < 3; ++c) {
        const float value = image.pixel(row, column)[c];
        // A negative or non-finite texel would silently poison every irradiance value.
        if (!std::isfinite(value) || value < 0.0f)
          throw InputError(fmt::format("{}: texel (column {}, row {}) channel {} is {}; radiance must be finite "
                                       "and non-negative",
                                       path, column, row, channel[c], value));
        radiance(Eigen::Index(row) * image.width + column, c) = value;
      }
  return LatLongEnvironment(image.width, image.height, std::move(radiance));
}

double LatLongEnvironment::polarAngle(int row) const { return M_PI * (row + 0.5) / height_; }

double LatLongEnvironment::azimuth(int column) const { return M_PI * (2.0 * (column + 0.5) / width_ - 1.0); }

Eigen::Vector3d LatLongEnvironment::direction(int row, int column) const {
  const double phi = polarAngle(row), theta = azimuth(column);
  return {std::sin(phi) * std::sin(theta), std::cos(phi), -std::sin(phi) * std::cos(theta)};
}

double LatLongEnvironment::texelSolidAngle(int row) const {
  // sin(latitude) = cos(polar angle) at the texel's top and bottom edges.
  const double top = std::cos(M_PI * row / height_), bottom = std::cos(M_PI * (row + 1) / height_);
  return 2.0 * M_PI / width_ * std::abs(top - bottom);
}

DirectionSet LatLongEnvironment::texels() const {
  DirectionSet set;
  set.directions.reserve(texelCount());
  set.weights.reserve(texelCount());
  for (int row = 0; row < height_; ++row)
    for (int column = 0; column < width_; ++column) {
      set.directions.push_back(direction(row, column));
      set.weights.push_back(texelSolidAngle(row));
    }
  return set;
}

}  // namespace baker
