#include "basis/AmbientDiceYCoCg.h"

#include "basis/BasisRegistry.h"

namespace baker {

const SphericalFunctions& AmbientDiceYCoCg::functions(int channel) const {
  if (channel == 0) return luminance_;
  return chrominance_;
}

Eigen::Vector3f AmbientDiceYCoCg::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  const TrianglePoint p = Icosahedron::instance().locate(d);
  double local[9];
  luminance_.localWeights(p, local);
  const float* y = coefficients;
  const float* co = y + luminance_.count();
  const float* cg = co + chrominance_.count();
  double luma = 0.0, orange = 0.0, green = 0.0;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) luma += local[3 * k + j] * y[3 * p.vertices[k] + j];
    orange += p.spherical[k] * co[p.vertices[k]];
    green += p.spherical[k] * cg[p.vertices[k]];
  }
  return toRgb(ColorSpace::YCoCg, Eigen::Vector3f(float(luma), float(orange), float(green)));
}

namespace {

const BasisRegistration kYCoCg({50, {"ad-ycocg"}, {},
                                [](const std::string& name, const BasisParameters&) -> std::unique_ptr<Basis> {
                                  if (name == "ad-ycocg") return std::make_unique<AmbientDiceYCoCg>();
                                  return nullptr;
                                }});

}  // namespace

}  // namespace baker
