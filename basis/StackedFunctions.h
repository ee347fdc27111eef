#pragma once
#include <vector>

#include "basis/SphericalFunctions.h"

namespace baker {

// Several function sets one after another, as one set: one evaluation at a direction serves the
// moments of every set (a basis whose channels use different sets).
class StackedFunctions : public SphericalFunctions {
 public:
  StackedFunctions() = default;
  // The sets must outlive this object.
  explicit StackedFunctions(std::vector<const SphericalFunctions*> sets);

  int count() const override { return count_; }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  // Where set k's values start.
  int offset(int k) const { return offsets_[std::size_t(k)]; }

 private:
  std::vector<const SphericalFunctions*> sets_;
  std::vector<int> offsets_;
  int count_ = 0;
};

}  // namespace baker
