#pragma once

namespace baker {

// `baker info SCENE [--json] [--scene N] [--env FILE ... | --sky R,G,B]`: what the loader made
// of a scene (geometry, instances, materials by alpha mode, lights by type, textures, bounds,
// extensions used and ignored, environment) and which effects a bake would simulate, and why.
// argv[0] is "info".
int runInfoCommand(int argc, char** argv);

}  // namespace baker
