#include "validate/SignalMetrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "common/Error.h"

namespace baker {

SignalMetric parseSignalMetric(const std::string& name) {
  if (name == "rmae") return SignalMetric::Rmae;
  if (name == "rmse") return SignalMetric::Rmse;
  if (name == "ssim") return SignalMetric::Ssim;
  throw SettingError("metric", fmt::format("\"{}\": expected rmae, rmse or ssim", name));
}

const char* signalMetricName(SignalMetric metric) {
  switch (metric) {
    case SignalMetric::Rmae: return "rmae";
    case SignalMetric::Rmse: return "rmse";
    case SignalMetric::Ssim: return "ssim";
  }
  return "";
}

bool higherIsBetter(SignalMetric metric) { return metric == SignalMetric::Ssim; }

double relativeMeanAbsoluteError(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& reconstruction,
                                 int channels) {
  const auto y = reference.leftCols(channels);
  return (y - reconstruction.leftCols(channels)).cwiseAbs().sum() / y.sum();
}

double relativeRootMeanSquareError(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& reconstruction,
                                   int channels) {
  const auto y = reference.leftCols(channels);
  const double n = double(y.size());
  return std::sqrt((y - reconstruction.leftCols(channels)).squaredNorm() / n) / (y.sum() / n);
}

namespace {

constexpr int kWindow = 11;
constexpr double kWindowSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;  // (K·L)² with L = 1

std::array<double, kWindow> gaussianWindow() {
  std::array<double, kWindow> w{};
  double sum = 0.0;
  for (int i = 0; i < kWindow; ++i) sum += w[std::size_t(i)] = std::exp(-0.5 * std::pow((i - kWindow / 2) / kWindowSigma, 2));
  for (double& v : w) v /= sum;
  return w;
}

// The signal's value in direction d: bilinear between texel centres, wrapping in longitude.
Eigen::Vector3d lookUp(const LatLongEnvironment& image, const Eigen::Vector3d& d) {
  // Inverse of LatLongEnvironment::direction: d = (sin φ sin θ, cos φ, −sin φ cos θ).
  const double phi = std::acos(std::clamp(d.y(), -1.0, 1.0));
  const double theta = std::atan2(d.x(), -d.z());
  const double x = (theta / M_PI + 1.0) / 2.0 * image.width() - 0.5;
  const double y = std::clamp(phi / M_PI * image.height() - 0.5, 0.0, image.height() - 1.0);
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  auto texel = [&](int column, int row) {
    column = ((column % image.width()) + image.width()) % image.width();
    row = std::min(row, image.height() - 1);
    return Eigen::Vector3d(image.radiance().row(std::int64_t(row) * image.width() + column).transpose());
  };
  return (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
         fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

// The direction through pixel (x, y) of cube face `face` (+X, −X, +Y, −Y, +Z, −Z).
Eigen::Vector3d cubeDirection(int face, int x, int y) {
  const double u = 2.0 * (x + 0.5) / kSsimFaceSize - 1.0, v = 2.0 * (y + 0.5) / kSsimFaceSize - 1.0;
  switch (face) {
    case 0: return Eigen::Vector3d(1, -v, -u).normalized();
    case 1: return Eigen::Vector3d(-1, -v, u).normalized();
    case 2: return Eigen::Vector3d(u, 1, v).normalized();
    case 3: return Eigen::Vector3d(u, -1, -v).normalized();
    case 4: return Eigen::Vector3d(u, -v, 1).normalized();
    default: return Eigen::Vector3d(-u, -v, -1).normalized();
  }
}

// SSIM compares what a viewer would see, so bright sources are compressed as a display would and
// a negative reconstruction shows as black (the header has the mapping).
double displayed(const Eigen::Vector3d& value, bool scalar, double exposure) {
  if (scalar) return std::clamp(value.x(), 0.0, 1.0);
  Eigen::Vector3d mapped;
  for (int c = 0; c < 3; ++c) {
    const double x = exposure * std::max(value[c], 0.0);
    mapped[c] = x / (1.0 + x);
  }
  return mapped.dot(Eigen::Vector3d(0.2126, 0.7152, 0.0722));
}

}  // namespace

double structuralSimilarity(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.rows() < kWindow || a.cols() < kWindow)
    throw std::invalid_argument("structuralSimilarity: two images of the same size, at least 11 × 11, are needed");
  static const std::array<double, kWindow> w = gaussianWindow();
  double sum = 0.0;
  int windows = 0;
  for (int y = 0; y + kWindow <= a.rows(); ++y)
    for (int x = 0; x + kWindow <= a.cols(); ++x) {
      double ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
      for (int j = 0; j < kWindow; ++j)
        for (int i = 0; i < kWindow; ++i) {
          const double weight = w[std::size_t(j)] * w[std::size_t(i)];
          const double va = a(y + j, x + i), vb = b(y + j, x + i);
          ma += weight * va;
          mb += weight * vb;
          aa += weight * va * va;
          bb += weight * vb * vb;
          ab += weight * va * vb;
        }
      const double varA = aa - ma * ma, varB = bb - mb * mb, cov = ab - ma * mb;
      sum += (2 * ma * mb + kC1) * (2 * cov + kC2) / ((ma * ma + mb * mb + kC1) * (varA + varB + kC2));
      ++windows;
    }
  return sum / windows;
}

double signalScore(const SphereSignal& signal, const FittedSignal& fit, SignalMetric metric) {
  const int channels = signal.scalar ? 1 : 3;
  if (metric != SignalMetric::Ssim) {
    const Eigen::MatrixX3d reconstruction = fit.atTexels(signal.image);
    return metric == SignalMetric::Rmae ? relativeMeanAbsoluteError(signal.image.radiance(), reconstruction, channels)
                                        : relativeRootMeanSquareError(signal.image.radiance(), reconstruction, channels);
  }
  const DirectionSet texels = signal.image.texels();
  double luminance = 0.0;
  for (std::size_t t = 0; t < texels.size(); ++t)
    luminance += texels.weights[t] * signal.image.radiance().row(std::int64_t(t)).dot(Eigen::RowVector3d(0.2126, 0.7152, 0.0722));
  luminance /= 4.0 * M_PI;
  const double exposure = luminance > 0.0 ? 0.18 / luminance : 1.0;
  double sum = 0.0;
  for (int face = 0; face < 6; ++face) {
    Eigen::MatrixXd reference(kSsimFaceSize, kSsimFaceSize), reconstruction(kSsimFaceSize, kSsimFaceSize);
    for (int y = 0; y < kSsimFaceSize; ++y)
      for (int x = 0; x < kSsimFaceSize; ++x) {
        const Eigen::Vector3d d = cubeDirection(face, x, y);
        reference(y, x) = displayed(lookUp(signal.image, d), signal.scalar, exposure);
        reconstruction(y, x) = displayed(fit.at(d), signal.scalar, exposure);
      }
    sum += structuralSimilarity(reference, reconstruction);
  }
  return sum / 6.0;
}

}  // namespace baker
