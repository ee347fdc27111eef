#include "formats/VolumeReconstruction.h"

#include <stdexcept>

#include "formats/VolumeReader.h"
#include "formats/VolumeSampler.h"

namespace baker {

VolumeReconstruction::VolumeReconstruction(const Volume& volume)
    : VolumeReconstruction(basisOf(volume), storedSignalOf(volume.settings)) {}

VolumeReconstruction::VolumeReconstruction(std::unique_ptr<Basis> basis, StoredSignal signal)
    : basis_(std::move(basis)), signal_(signal) {
  if (signal_ != StoredSignal::Radiance) return;
  for (int c = 0; c < 3; ++c) {
    if (c > 0 && &basis_->functions(c) == &basis_->functions(c - 1))
      responses_.push_back(responses_.back());
    else
      responses_.push_back(std::make_shared<const DiffuseResponse>(basis_->functions(c), basis_->name()));
  }
}

double VolumeReconstruction::diffuse(int channel, const float* coefficients, const Eigen::Vector3d& normal) const {
  const DiffuseResponse& response = *responses_[std::size_t(channel)];
  thread_local std::vector<double> k;
  k.resize(std::size_t(response.count()));
  response.evaluate(normal, k.data());
  double sum = 0.0;
  for (int i = 0; i < response.count(); ++i) sum += k[std::size_t(i)] * double(coefficients[i]);
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

Eigen::Vector3f VolumeReconstruction::radiance(const float* coefficients, const Eigen::Vector3d& direction) const {
  if (signal_ != StoredSignal::Radiance) throw std::logic_error("an irradiance volume holds no radiance");
  return basis_->reconstruct(coefficients, direction);
}

}  // namespace baker
