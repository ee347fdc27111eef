#pragma once
#include <tiny_gltf.h>

#include <Eigen/Core>
#include <optional>
#include <string>

#include "scene/PunctualLight.h"

namespace baker {

// The KHR_lights_punctual light node `node` places, if any, at its world transform `world`:
// position from the translation, direction along the node's −Z. A malformed light (unknown
// type, negative intensity, cone angles outside 0 ≤ inner ≤ outer ≤ π/2, a missing index) is an
// InputError naming the glTF path.
std::optional<PunctualLight> readLight(const tinygltf::Model& model, int node, const Eigen::Matrix4d& world,
                                       const std::string& file);

}  // namespace baker
