#include "bake/BasisRegistry.h"

#include <fmt/format.h>

#include <cmath>

#include "bake/AmbientCubeBasis.h"
#include "bake/AmbientDiceBezier.h"
#include "bake/AmbientDiceLinear.h"
#include "bake/AmbientDiceSrbf.h"
#include "bake/AmbientDiceYCoCg.h"
#include "bake/ShBasis.h"
#include "bake/SphericalGaussianBasis.h"
#include "common/Error.h"

namespace baker {

std::vector<std::string> basisNames() {
  std::vector<std::string> names;
  for (int l = 0; l <= 8; ++l) names.push_back("sh-l" + std::to_string(l));
  for (const char* name : {"ad-linear", "ad-cos2", "ad-srbf", "ad-rgb", "ad-rgb-flat", "ad-ycocg"}) names.push_back(name);
  names.push_back("ambient-cube");
  // sg-N takes any N in 1..64; the list names the counts whose default sharpness was measured.
  for (int n : SphericalGaussianBasis::measuredLobeCounts()) names.push_back("sg-" + std::to_string(n));
  return names;
}

std::unique_ptr<Basis> makeBasis(const std::string& name) {
  for (int l = 0; l <= 8; ++l)
    if (name == "sh-l" + std::to_string(l)) return std::make_unique<ShBasis>(l);
  if (name == "ad-linear") return std::make_unique<AmbientDiceLinear>();
  if (name == "ad-cos2") return std::make_unique<AmbientDiceSrbf>(name, 1.0, 0.0);
  if (name == "ad-srbf") return std::make_unique<AmbientDiceSrbf>(name, 0.7, 0.3);
  if (name == "ad-rgb") return std::make_unique<AmbientDiceBezier>(Barycentrics::Spherical);
  if (name == "ad-rgb-flat") return std::make_unique<AmbientDiceBezier>(Barycentrics::Flat);
  if (name == "ad-ycocg") return std::make_unique<AmbientDiceYCoCg>();
  if (name == "ambient-cube") return std::make_unique<AmbientCubeBasis>();
  if (const int lobes = sphericalGaussianLobeCount(name)) return std::make_unique<SphericalGaussianBasis>(lobes);
  throw InputError(fmt::format("unknown basis '{}' (known: {})", name, fmt::join(basisNames(), ", ")));
}

std::unique_ptr<Basis> makeBasis(const std::string& name, double sgSharpness) {
  if (sgSharpness == 0.0) return makeBasis(name);
  const int lobes = sphericalGaussianLobeCount(name);
  if (lobes == 0) throw InputError(fmt::format("--sg-sharpness applies to sg-N bases only, not '{}'", name));
  if (!(sgSharpness > 0.0) || !std::isfinite(sgSharpness))
    throw InputError(fmt::format("--sg-sharpness must be a positive number, got {}", sgSharpness));
  return std::make_unique<SphericalGaussianBasis>(lobes, sgSharpness);
}

}  // namespace baker
