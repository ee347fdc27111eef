#include "validate/SpecularOnEnvironment.h"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <tbb/parallel_for.h>

#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"
#include "basis/GgxLobe.h"
#include "common/Error.h"
#include "formats/VolumeReconstruction.h"
#include "validate/SphereSignals.h"

namespace baker {
namespace {

constexpr int kNormals = 16;
constexpr double kCosViews[3] = {1.0, 0.7, 0.3};
// A lobe this many texels wide (α against the texels' angular size) is summed over the texels,
// each seen at its centre; a narrower one by its own quadrature (basis/GgxLobe.h), whose nodes
// are then dense against the texels. A sparse set of nodes over a wide lobe would alias a small
// bright source: on grace at roughness 1, sh-l4's error reads 133 % against the nodes and 21 %
// against the texel sum.
constexpr double kTexelsPerLobe = 8.0;
constexpr int kLobeNodes = 64, kLobePhi = 128;

// The texel a direction falls in (the inverse of LatLongEnvironment::direction).
Eigen::Vector3d radianceAt(const LatLongEnvironment& image, const Eigen::Vector3d& d) {
  const double polar = std::acos(std::clamp(d.y(), -1.0, 1.0));
  const double azimuth = std::atan2(d.x(), -d.z());
  const int row = std::clamp(int(polar / M_PI * image.height()), 0, image.height() - 1);
  const int column = std::clamp(int((azimuth / M_PI + 1.0) / 2.0 * image.width()), 0, image.width() - 1);
  return image.radiance().row(std::int64_t(row) * image.width() + column).transpose();
}

// RMSE over the rows and columns of `fit` − `reference`, over the reference's mean; none when the
// reference is black (narrow lobes can all miss a small source the normals still see).
std::optional<double> relativeRmse(const Eigen::MatrixX3d& fit, const Eigen::MatrixX3d& reference) {
  const double mean = reference.mean();
  if (!(mean > 0.0)) return std::nullopt;
  return std::sqrt((fit - reference).squaredNorm() / double(reference.size())) / mean;
}

// The references over texels already listed (LatLongEnvironment::texels), as the public ones.
Eigen::Vector3d irradianceOverTexels(const LatLongEnvironment& image, const DirectionSet& texels, const Eigen::Vector3d& normal) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t t = 0; t < texels.size(); ++t) {
    const double cosine = normal.dot(texels.directions[t]);
    if (cosine > 0.0) sum += cosine * texels.weights[t] * image.radiance().row(Eigen::Index(t)).transpose();
  }
  return sum;
}

Eigen::Vector3d specularOverTexels(const LatLongEnvironment& image, const DirectionSet& texels, const SpecularFrame& frame,
                                   double roughness) {
  const GgxLobe lobe(frame.normal, frame.view, roughness);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double weights = 0.0;
  if (roughness * roughness >= kTexelsPerLobe * 2.0 * M_PI / image.width()) {
    for (std::size_t t = 0; t < texels.size(); ++t) {
      const double w = texels.weights[t] * lobe.cosineWeighted(texels.directions[t]);
      if (w == 0.0) continue;
      sum += w * image.radiance().row(Eigen::Index(t)).transpose();
      weights += w;
    }
    return sum / weights;
  }
  const DirectionSet nodes = lobe.quadrature(kLobeNodes, kLobePhi);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    sum += nodes.weights[k] * radianceAt(image, nodes.directions[k]);
    weights += nodes.weights[k];
  }
  return sum / weights;
}

}  // namespace

Eigen::Vector3d exactIrradianceAt(const LatLongEnvironment& image, const Eigen::Vector3d& normal) {
  return irradianceOverTexels(image, image.texels(), normal);
}

Eigen::Vector3d exactSpecularAt(const LatLongEnvironment& image, const SpecularFrame& frame, double roughness) {
  return specularOverTexels(image, image.texels(), frame, roughness);
}

std::vector<SpecularFrame> specularFrames() {
  const DirectionSet normals = sphericalFibonacci(kNormals);
  std::vector<SpecularFrame> frames;
  for (int i = 0; i < kNormals; ++i) {
    const Eigen::Vector3d n = normals.directions[std::size_t(i)];
    const Eigen::Vector3d t0 = n.unitOrthogonal(), t1 = n.cross(t0);
    const double turn = M_PI * (3.0 - std::sqrt(5.0)) * i;
    const Eigen::Vector3d tangent = std::cos(turn) * t0 + std::sin(turn) * t1;
    for (double c : kCosViews) frames.push_back({n, c * n + std::sqrt(1.0 - c * c) * tangent});
  }
  return frames;
}

std::vector<SpecularFrame> upwardFrames(const Eigen::Vector3d& up) {
  constexpr int kTurns = 8;
  const Eigen::Vector3d t0 = up.unitOrthogonal(), t1 = up.cross(t0);
  std::vector<SpecularFrame> frames;
  for (int i = 0; i < kTurns; ++i) {
    const double turn = 2.0 * M_PI * i / kTurns;
    const Eigen::Vector3d tangent = std::cos(turn) * t0 + std::sin(turn) * t1;
    for (double c : kCosViews) frames.push_back({up, c * up + std::sqrt(1.0 - c * c) * tangent});
  }
  return frames;
}

std::vector<EnvironmentSpecularScore> scoreSpecularOnEnvironment(const Basis& basis, const LatLongEnvironment& image,
                                                                 const std::string& path, const std::vector<double>& roughness,
                                                                 const std::vector<SpecularFrame>& frames) {
  // The fit's resolution is checked before the references' long sums.
  const SphereSignal signal{path, areaDownsampled(image, kSignalWidth, path), false};
  const Eigen::Index count = Eigen::Index(frames.size());
  Eigen::MatrixX3d diffuseReference(count, 3);
  std::vector<Eigen::MatrixX3d> specularReference(roughness.size(), Eigen::MatrixX3d(count, 3));
  const DirectionSet texels = image.texels();
  // Each frame is its own sum, so the references are the same at any thread count.
  tbb::parallel_for(Eigen::Index(0), count, [&](Eigen::Index f) {
    const SpecularFrame& frame = frames[std::size_t(f)];
    diffuseReference.row(f) = irradianceOverTexels(image, texels, frame.normal).transpose();
    for (std::size_t r = 0; r < roughness.size(); ++r)
      specularReference[r].row(f) = specularOverTexels(image, texels, frame, roughness[r]).transpose();
  });
  // A relative error needs light to be relative to.
  if (!(diffuseReference.mean() > 0.0))
    throw InputError(fmt::format("{}: no light reaches the surfaces read, so there is no error to measure relative to it", path));
  const VolumeReconstruction reading(makeBasisLike(basis), StoredSignal::Radiance);
  std::vector<EnvironmentSpecularScore> scores;
  for (FitMethod method : {FitMethod::Linear, FitMethod::NonNegative}) {
    if (!fitApplies(basis, method)) continue;
    const FittedSignal fit(basis, signal, method);
    const float* c = fit.coefficients().data();
    EnvironmentSpecularScore score{method, fit.bytesPerProbe(), 0.0, {}};
    Eigen::MatrixX3d diffuse(count, 3);
    for (Eigen::Index f = 0; f < count; ++f)
      diffuse.row(f) = reading.irradiance(c, frames[std::size_t(f)].normal).cast<double>().transpose();
    score.diffuseRelativeRmse = *relativeRmse(diffuse, diffuseReference);
    for (std::size_t r = 0; r < roughness.size(); ++r) {
      Eigen::MatrixX3d specular(count, 3);
      for (Eigen::Index f = 0; f < count; ++f) {
        const SpecularFrame& frame = frames[std::size_t(f)];
        specular.row(f) = reading.specular(c, frame.normal, frame.view, roughness[r]).value.cast<double>().transpose();
      }
      score.specularRelativeRmse.push_back(relativeRmse(specular, specularReference[r]));
    }
    scores.push_back(std::move(score));
  }
  return scores;
}

}  // namespace baker
