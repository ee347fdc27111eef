#include "cli/RelightCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/CommandLine.h"
#include "relight/Relighting.h"

namespace baker {

int runRelightCommand(int argc, char** argv) {
  CLI::App app{"Relight a volume to another sky without a rebake: the sky it was baked under is taken away and the "
               "new one added through each probe's stored sky visibility; the light the sky sent off surfaces is "
               "scaled to the new sky, approximately. Lamps and emission are kept as baked (docs/RELIGHTING.md)."};
  RelightRequest request;
  std::string outPath, format, precision = "half";
  bool json = false;
  app.add_option("volume", request.volumePath, "the volume baker wrote (.vdb file or EXR slice directory)")->required();
  app.add_option("--env", request.sky.environmentMap,
                 "the new lat-long environment map (.hdr/.exr; +Y up, image centre along +X, u = 0.75 along +Z)");
  app.add_option("--env-intensity", request.sky.environmentIntensity, "multiplier on the new map")->capture_default_str();
  app.add_option("--env-rotation", request.sky.environmentRotation,
                 "rotation of the new map about +Y in degrees (right-handed)")
      ->capture_default_str();
  app.add_option("--sky", request.sky.sky, "a constant sky radiance r,g,b instead of a map (0,0,0: no sky)");
  app.add_option("--out", outPath, "output volume: a .vdb file or a directory")->required();
  app.add_option("--format", format, "vdb, exr, bevy or threejs; default: from --out (.vdb: vdb, else exr)");
  app.add_option("--precision", precision, "EXR slices: half or float")->capture_default_str();
  app.add_flag("--json", json, "print the summary as JSON on stdout");
  return runGuarded("baker relight", app, argc, argv, [&]() {
    request.output = volumeOutput("", outPath, format, precision);
    const RelightReport r = relightVolumeFile(request);
    for (const std::string& w : r.warnings) std::cerr << "baker relight: warning: " << w << "\n";
    if (json) {
      std::cout << nlohmann::json{{"output", request.output.path},
                                  {"format", volumeFormatName(request.output.format)},
                                  {"basis", r.basis},
                                  {"signal", r.signal},
                                  {"levels", r.levels},
                                  {"probes", r.probes},
                                  {"from_sky", r.fromSky},
                                  {"to_sky", r.toSky},
                                  {"baked_sky", r.bakedSky},
                                  {"bounces", r.bounces},
                                  {"other_lights", r.otherLights},
                                  {"visibility", r.visibility},
                                  {"old_sky_removed", r.oldSkyRemoved},
                                  {"bounce_scaled", r.bounceScaled},
                                  {"changes", r.changes},
                                  {"keeps", r.keeps},
                                  {"seconds", r.seconds}}
                       .dump(2)
                << "\n";
      return 0;
    }
    std::cout << fmt::format("wrote {} ({}, {}, {} probes): relit from {} to {} in {:.2f} s\n", request.output.path,
                             r.basis, r.signal, r.probes, r.fromSky, r.toSky, r.seconds);
    for (const std::string& c : r.changes) std::cout << "  changed: " << c << "\n";
    for (const std::string& k : r.keeps) std::cout << "  kept:    " << k << "\n";
    if (!r.engineExport.engine.empty())
      std::cout << fmt::format("  for {}: {}\n", r.engineExport.engine, r.engineExport.conversion);
    return 0;
  });
}

}  // namespace baker
