#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "validate/SphereSignals.h"

namespace baker {

// How coefficients are found from a signal's texels: least squares over the sphere (texels
// weighted by solid angle; for SH this is the projection the thesis uses, up to the texel
// sum), or the same restricted to non-negative coefficients, for bases whose functions are
// non-negative (NonNegativeProjection.h; for YCoCg the chroma channels stay linear, as the bake
// does).
enum class FitMethod { Linear, NonNegative };
const char* fitMethodName(FitMethod method);
// Whether `method` applies to `basis` (non-negative fits need non-negative functions).
bool fitApplies(const Basis& basis, FitMethod method);

// A signal expressed in a basis: its coefficients, and the reconstruction anywhere.
class FittedSignal {
 public:
  // NumericalError naming the basis when the texels cannot resolve its functions.
  FittedSignal(const Basis& basis, const SphereSignal& signal, FitMethod method);

  // The reconstruction in direction d (RGB; a scalar signal in all three).
  Eigen::Vector3d at(const Eigen::Vector3d& d) const;
  // At every texel of the signal's image, in texel order.
  Eigen::MatrixX3d atTexels(const LatLongEnvironment& layout) const;
  // Bytes one probe stores at 32-bit floats: every channel's coefficients, or only the first
  // function set's for a scalar signal.
  int bytesPerProbe() const { return 4 * storedCoefficients_; }
  // One probe's coefficients in the basis's layout (a scalar signal's in channel 0 only).
  const std::vector<float>& coefficients() const { return coefficients_; }

 private:
  const Basis& basis_;
  bool scalar_;
  std::vector<float> coefficients_;
  int storedCoefficients_ = 0;
};

}  // namespace baker
