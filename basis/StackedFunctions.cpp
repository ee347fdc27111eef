#include "basis/StackedFunctions.h"

namespace baker {

StackedFunctions::StackedFunctions(std::vector<const SphericalFunctions*> sets) : sets_(std::move(sets)) {
  for (const SphericalFunctions* set : sets_) {
    offsets_.push_back(count_);
    count_ += set->count();
  }
}

void StackedFunctions::evaluate(const Eigen::Vector3d& direction, double* values) const {
  for (std::size_t k = 0; k < sets_.size(); ++k) sets_[k]->evaluate(direction, values + offsets_[k]);
}

}  // namespace baker
