#include "basis/BasisRegistry.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

std::unique_ptr<Basis> makeBasis(const std::string& name, const BasisParameters& given) {
  BasisParameters parameters = given;
  if (const std::optional<double>& s = parameters.sharpness; s && !(*s > 0.0 && std::isfinite(*s)))
    throw SettingError("sg_sharpness", fmt::format("must be a positive number, got {}", *s));
  if (std::optional<Eigen::Vector3d>& axis = parameters.hemisphereAxis) {
    if (!(axis->allFinite() && axis->norm() > 0.0))
      throw SettingError("hemisphere_axis", fmt::format("must be a finite direction, not zero, got {},{},{}", axis->x(),
                                                        axis->y(), axis->z()));
    // A unit axis (as a volume records it) is kept bit for bit: normalising again can move its last bit.
    if (std::abs(axis->squaredNorm() - 1.0) > 4.0 * std::numeric_limits<double>::epsilon()) axis->normalize();
  }
  for (const BasisFamily& family : families()) {
    std::unique_ptr<Basis> basis = family.make(name, parameters);
    if (!basis) continue;
    for (const auto& [key, value] : parameterSettings(parameters))
      if (std::find(family.takes.begin(), family.takes.end(), key) == family.takes.end())
        throw SettingError(key, fmt::format("does not apply to '{}'", name));
    return basis;
  }
  throw SettingError("basis", fmt::format("'{}' is not a basis (known: {})", name, fmt::join(basisNames(), ", ")));
}

std::unique_ptr<Basis> makeBasisLike(const Basis& basis) { return makeBasis(basis.name(), basis.parameters()); }

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
