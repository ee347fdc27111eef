#include "bake/BasisRegistry.h"

#include <fmt/format.h>

#include "bake/ShBasis.h"
#include "common/Error.h"

namespace baker {

std::vector<std::string> basisNames() {
  std::vector<std::string> names;
  for (int l = 0; l <= 8; ++l) names.push_back("sh-l" + std::to_string(l));
  return names;
}

std::unique_ptr<Basis> makeBasis(const std::string& name) {
  for (int l = 0; l <= 8; ++l)
    if (name == "sh-l" + std::to_string(l)) return std::make_unique<ShBasis>(l);
  throw InputError(fmt::format("unknown basis '{}' (known: {})", name, fmt::join(basisNames(), ", ")));
}

}  // namespace baker
