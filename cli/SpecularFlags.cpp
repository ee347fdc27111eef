#include "cli/SpecularFlags.h"

#include <fmt/format.h>

#include "cli/CommandLine.h"
#include "common/Error.h"

namespace baker {

void SpecularFlags::addTo(CLI::App& app) {
  app.add_option("--roughness", roughness,
                 "with --view: GGX specular (F0 = 1) of a radiance volume at this roughness, 0 (mirror) to 1");
  app.add_option("--view", viewText, "with --roughness: direction from the surface to the eye, x,y,z");
}

std::optional<SpecularRequest> specularRequest(const SpecularFlags& flags) {
  if (!flags.roughness && flags.viewText.empty()) return std::nullopt;
  if (!flags.roughness || flags.viewText.empty())
    throw InputError("--roughness and --view go together: specular needs both");
  if (!(*flags.roughness >= 0.0 && *flags.roughness <= 1.0))
    throw InputError(fmt::format("--roughness must be in [0, 1], got {}", *flags.roughness));
  return SpecularRequest{*flags.roughness, parseDirection("--view", flags.viewText)};
}

}  // namespace baker
