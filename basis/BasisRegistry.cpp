#include "basis/BasisRegistry.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "basis/NonNegativeProjection.h"
#include "common/Error.h"

namespace baker {
namespace {

// Built on first use, so that registrations from any file's static initialisation find it.
std::vector<BasisFamily>& families() {
  static std::vector<BasisFamily> registered;
  return registered;
}

}  // namespace

BasisRegistration::BasisRegistration(BasisFamily family) {
  std::vector<BasisFamily>& all = families();
  const auto after = std::upper_bound(all.begin(), all.end(), family.listOrder,
                                      [](int order, const BasisFamily& f) { return order < f.listOrder; });
  all.insert(after, std::move(family));
}

std::vector<std::string> basisNames() {
  std::vector<std::string> names;
  for (const BasisFamily& family : families())
    names.insert(names.end(), family.listedNames.begin(), family.listedNames.end());
  return names;
}

std::unique_ptr<Basis> makeBasis(const std::string& name, const std::optional<double>& sharpness) {
  if (sharpness && !(*sharpness > 0.0 && std::isfinite(*sharpness)))
    throw SettingError("sg_sharpness", fmt::format("must be a positive number, got {}", *sharpness));
  for (const BasisFamily& family : families()) {
    std::unique_ptr<Basis> basis = family.make(name, BasisParameters{family.takesSharpness ? sharpness : std::nullopt});
    if (!basis) continue;
    if (sharpness && !family.takesSharpness)
      throw SettingError("sg_sharpness", fmt::format("applies to sg-N bases only, not '{}'", name));
    return basis;
  }
  throw SettingError("basis", fmt::format("'{}' is not a basis (known: {})", name, fmt::join(basisNames(), ", ")));
}

bool admitsNonNegativeFit(const Basis& basis) {
  const int constrainedChannels = basis.colorSpace() == ColorSpace::Rgb ? 3 : 1;
  for (int c = 0; c < constrainedChannels; ++c)
    if (!functionsAreNonNegative(basis.functions(c))) return false;
  return true;
}

std::vector<std::string> nonNegativeBasisNames() {
  std::vector<std::string> names;
  for (const std::string& name : basisNames())
    if (admitsNonNegativeFit(*makeBasis(name))) names.push_back(name);
  return names;
}

}  // namespace baker
