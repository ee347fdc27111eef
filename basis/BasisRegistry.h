#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "basis/Basis.h"

namespace baker {

// One family of bases as it registers itself, in its own file (BasisRegistration): the names
// it lists, where they come in basisNames(), which parameters apply (by their settings' keys,
// basis/BasisParameters.h), and how it makes a basis from a name (nullptr when the name is not
// one of its own).
struct BasisFamily {
  int listOrder = 0;
  std::vector<std::string> listedNames;
  std::vector<std::string> takes;
  std::function<std::unique_ptr<Basis>(const std::string& name, const BasisParameters& parameters)> make;
};

// Defined at namespace scope in a basis's file, it adds the family before main() runs; the
// library is linked whole (CMakeLists.txt) so that no registration is dropped.
class BasisRegistration {
 public:
  explicit BasisRegistration(BasisFamily family);
};

// Every basis a bake accepts by name, in the families' order.
std::vector<std::string> basisNames();
// SettingError "basis" listing the valid names when `name` is unknown; SettingError naming the
// parameter ("sg_sharpness", "hemisphere_axis") when one is given to a basis it does not apply to
// or is out of range: a sharpness not positive, an axis zero or not finite (it is normalised).
std::unique_ptr<Basis> makeBasis(const std::string& name, const BasisParameters& parameters = {});
// The same basis again, for a reader that owns its own.
std::unique_ptr<Basis> makeBasisLike(const Basis& basis);

// The constrained (c >= 0) fit serves a basis only when the functions it constrains are all
// >= 0: R, G and B (each in its channel's functions), or Y.
bool admitsNonNegativeFit(const Basis& basis);
// The listed bases it serves.
std::vector<std::string> nonNegativeBasisNames();

}  // namespace baker
