#include "cli/ViewCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/CommandLine.h"
#include "formats/VolumeReader.h"
#include "viewer/PageServer.h"
#include "viewer/ViewerPage.h"

namespace baker {

int runViewCommand(int argc, char** argv) {
  CLI::App app{"Write a page that shows a volume in a browser: its scene, a sphere per probe shaded by the volume, "
               "slices, probe states, relocations and sky visibility."};
  std::string volumePath, gltf, out;
  int port = 8080;
  bool json = false;
  app.add_option("volume", volumePath, "volume: .vdb, a directory of EXR slices, or an engine export")->required();
  app.add_option("--gltf", gltf, "the glTF scene; default: the scene the volume names, when it is beside the volume");
  app.add_option("--out", out, "directory to write the page into")->required();
  auto* serve = app.add_option("--serve", port, "serve the page on 127.0.0.1 at this port (0: any free) and print "
                                                "its address; runs until interrupted")
                    ->expected(0, 1)
                    ->default_str("8080")
                    ->check(CLI::Range(0, 65535));
  app.add_flag("--json", json, "print what was written as JSON on stdout");
  return runGuarded("baker view", app, argc, argv, [&]() {
    const AdaptiveVolume levels = readLevels(volumePath);
    const Volume& volume = levels.coarsest();
    const std::string scene = sceneOfVolume(volume, volumePath, gltf);
    writeViewerPage(levels, {volumePath, scene, out});
    std::int64_t probes = 0;
    for (const Volume& level : levels.levels) probes += level.rows.count(level.grid);
    if (json) {
      std::cout << nlohmann::json({{"page", out}, {"volume", volumePath}, {"scene", scene.empty() ? nlohmann::json(nullptr) : nlohmann::json(scene)}, {"basis", volume.basisName}, {"levels", levels.levels.size()}, {"probes", probes}}).dump(2) << "\n";
    } else {
      std::cout << fmt::format("wrote {} ({} probes{} of {}{}): open {}/index.html through a local server, or "
                               "use --serve\n",
                               out, probes,
                               levels.levels.size() > 1 ? fmt::format(" in {} levels", levels.levels.size()) : "",
                               volume.basisName, scene.empty() ? ", no scene: pass --gltf" : ", scene " + scene, out);
    }
    if (!serve->count()) return 0;
    servePage(out, port, [&](const std::string& url) {
      std::cerr << fmt::format("serving {} at {} (Ctrl-C stops)\n", out, url);
      std::cout << url << std::endl;
    });
    return 0;
  });
}

}  // namespace baker
