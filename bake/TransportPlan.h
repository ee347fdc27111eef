#pragma once
#include <string>
#include <vector>

#include "bake/Transport.h"
#include "scene/SceneEffects.h"

namespace baker {

// SettingError "turned_off" for a name that is not an effect's key ('-' or '_' alike), listing the keys.
void requireKnownEffects(const std::vector<std::string>& names);

// Turns off the effects the request names (requireKnownEffects first), saying so in their reason.

void turnOffEffects(std::vector<PlannedEffect>& plan, const std::vector<std::string>& names);

// The simulation the plan describes, with at most `bounces` diffuse reflections (none when the
// bounces effect is off; 0 bounces turns it off in the plan). `bounces` is a checked count
// (validateBakeRequest: 0..kMaxBounces).
TransportSettings transportSettings(std::vector<PlannedEffect>& plan, int bounces, std::uint64_t seed);

}  // namespace baker
