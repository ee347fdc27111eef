#pragma once
#include <Eigen/Core>

namespace baker {

// A finite set of real functions on the unit sphere, evaluated all at once at a direction.
// Bases are built from these; projection operators only ever see this interface.
class SphericalFunctions {
 public:
  virtual ~SphericalFunctions() = default;
  virtual int count() const = 0;
  // Writes count() values for the unit vector `direction`.
  virtual void evaluate(const Eigen::Vector3d& direction, double* values) const = 0;
};

}  // namespace baker
