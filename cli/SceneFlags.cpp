#include "cli/SceneFlags.h"

#include <string>

namespace baker {

void addSceneFlags(CLI::App& app, SceneOptions& options) {
  const CLI::Validator sceneIndex(
      [](std::string& value) {
        return !value.empty() && value.find_first_not_of("0123456789") == std::string::npos
                   ? std::string()
                   : "must be a scene index (0, 1, ...), got " + value;
      },
      "INDEX");
  app.add_option("--scene", options.scene, "glTF scene to load; default: the file's default scene")->check(sceneIndex);
  app.add_option("--env", options.environmentMap,
                 "lat-long environment map (.hdr/.exr; +Y up, image centre along +X, u = 0.75 along +Z)");
  app.add_option("--env-intensity", options.environmentIntensity, "multiplier on the environment map")
      ->capture_default_str();
  app.add_option("--env-rotation", options.environmentRotation,
                 "rotation of the environment map about +Y in degrees (right-handed)")
      ->capture_default_str();
  app.add_option("--sky", options.sky, "constant sky radiance r,g,b instead of a map");
}

}  // namespace baker
