#include "formats/VolumeReconstruction.h"

#include <cmath>
#include <stdexcept>

#include "basis/GgxLobe.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeSampler.h"

namespace baker {

VolumeReconstruction::VolumeReconstruction(const Volume& volume)
    : VolumeReconstruction(basisOf(volume), storedSignalOf(volume.settings)) {}

VolumeReconstruction::VolumeReconstruction(std::unique_ptr<Basis> basis, StoredSignal signal)
    : basis_(std::move(basis)), signal_(signal) {
  if (signal_ != StoredSignal::Radiance) return;
  for (int c = 0; c < 3; ++c) responses_.push_back(diffuseResponseOf(*basis_, c));
}

namespace {

// Readers ask for the same few normals at probe after probe (the six axes, the comparison's 26):
// each thread keeps the responses it evaluated last, so a lookup is a dot product.
const std::vector<double>& responseAt(const DiffuseResponse& response, const Eigen::Vector3d& normal) {
  struct Entry {
    const DiffuseResponse* response;
    Eigen::Vector3d normal;
    std::vector<double> values;
  };
  constexpr std::size_t kKept = 64;
  thread_local std::vector<Entry> kept;
  for (const Entry& e : kept)
    if (e.response == &response && e.normal == normal) return e.values;
  if (kept.size() == kKept) kept.erase(kept.begin());
  kept.push_back({&response, normal, std::vector<double>(std::size_t(response.count()))});
  response.evaluate(normal, kept.back().values.data());
  return kept.back().values;
}

}  // namespace

double VolumeReconstruction::diffuse(int channel, const float* coefficients, const Eigen::Vector3d& normal) const {
  const std::vector<double>& k = responseAt(*responses_[std::size_t(channel)], normal);
  double sum = 0.0;
  for (std::size_t i = 0; i < k.size(); ++i) sum += k[i] * double(coefficients[i]);
  return sum;
}

Eigen::Vector3f VolumeReconstruction::irradiance(const float* coefficients, const Eigen::Vector3d& normal) const {
  if (signal_ == StoredSignal::Irradiance) return basis_->reconstruct(coefficients, normal);
  Eigen::Vector3f e;
  for (int c = 0; c < 3; ++c) e[c] = float(diffuse(c, coefficients + basis_->coefficientOffset(c), normal));
  return toRgb(basis_->colorSpace(), e);
}

double VolumeReconstruction::skyVisibility(const float* visibility, const Eigen::Vector3d& normal) const {
  if (signal_ == StoredSignal::Irradiance) return reconstructVisibility(*basis_, visibility, normal);
  return diffuse(0, visibility, normal) / M_PI;
}

Eigen::Vector3f VolumeReconstruction::relitIrradiance(const float* rest, const float* visibility,
                                                      const Eigen::Vector3d& normal, const SkyHarmonics& sky) const {
  return (irradiance(rest, normal).cast<double>() + skyVisibility(visibility, normal) * sky.irradiance(normal))
      .cast<float>();
}

Eigen::Vector3f VolumeReconstruction::radiance(const float* coefficients, const Eigen::Vector3d& direction) const {
  if (signal_ != StoredSignal::Radiance) throw std::logic_error("an irradiance volume holds no radiance");
  return basis_->reconstruct(coefficients, direction);
}

VolumeReconstruction::Specular VolumeReconstruction::specular(const float* coefficients, const Eigen::Vector3d& normal,
                                                              const Eigen::Vector3d& view, double roughness) const {
  if (signal_ != StoredSignal::Radiance) throw std::logic_error("an irradiance volume holds no specular");
  std::call_once(blendFitted_, [&] { blend_ = specularBlendOf(*basis_); });
  const GgxLobe lobe(normal, view, roughness);  // the reflection of a view at or below the surface is kept above it
  Specular s;
  s.diffuseWeight = blend_->diffuseWeight(roughness, lobe.cosView());
  s.albedo = blend_->albedo(roughness, lobe.cosView());
  const float w = float(s.diffuseWeight);
  s.value = (1.0f - w) * radiance(coefficients, lobe.reflection()) + w * irradiance(coefficients, normal) / float(M_PI);
  return s;
}

}  // namespace baker
