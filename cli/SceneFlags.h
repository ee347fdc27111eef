#pragma once
#include <CLI/CLI.hpp>

#include "scene/SceneOptions.h"

namespace baker {

// Registers --scene, --env, --env-intensity, --env-rotation and --sky, the flags of every
// command that loads a scene.
void addSceneFlags(CLI::App& app, SceneOptions& options);

}  // namespace baker
