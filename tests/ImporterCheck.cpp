// An engine's importer as the layering promises it: it links formats (and through it basis and
// volume) and nothing that traces rays, reads a volume and evaluates its irradiance. Built
// to prove the link line (ctest Layers.ImporterLinksWithoutEmbree), and usable as a tool.
#include <cstdio>
#include <exception>

#include "formats/VolumeReader.h"
#include "formats/VolumeReconstruction.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: importer_check VOLUME\n");
    return 2;
  }
  try {
    const baker::Volume volume = baker::readVolume(argv[1]);
    // Whatever the volume stores (irradiance, or radiance whose diffuse response gives E).
    const baker::VolumeReconstruction reading(volume);
    const Eigen::Vector3f e = reading.irradiance(volume.probe(0), Eigen::Vector3d::UnitY());
    std::printf("%s: %lld probes in %s (%s); probe 0 E(+Y) = %g %g %g\n", argv[1],
                (long long)volume.grid.probeCount(), volume.basisName.c_str(), baker::storedSignalName(reading.signal()),
                e.x(), e.y(), e.z());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "importer_check: %s\n", e.what());
    return 2;
  }
}
