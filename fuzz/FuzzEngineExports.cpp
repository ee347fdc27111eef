// libFuzzer target: the engine-export readers (Bevy's KTX2 and its sidecar, three.js's JSON) on
// any bytes. The input's first byte picks the file it replaces (0: irradiance_volume.ktx2,
// 1: irradiance_volume.json, 2: light_probe_grid.json), beside the other files of small valid
// exports written once per process. An input must read or stop with InputError; anything else
// is a finding.
#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeWriter.h"
#include "fuzz/FuzzFiles.h"

namespace {

baker::Volume smallVolume(const baker::Basis& basis) {
  baker::Volume volume;
  volume.grid.dims = {2, 1, 2};  // the seeds in tests/fuzz_corpus/engine_exports are of this size
  volume.basisName = basis.name();
  volume.coefficientsPerProbe = basis.totalCoefficients();
  volume.coefficients.assign(std::size_t(volume.grid.probeCount()) * volume.coefficientsPerProbe, 0.5f);
  return volume;
}

bool writeExports(const baker::fuzz::FuzzDirectory& directory) {
  const auto cube = baker::makeBasis("ambient-cube"), sh = baker::makeBasis("sh-l2");
  baker::writeVolume(smallVolume(*cube), *cube, {directory.path() + "/bevy", baker::VolumeFormat::Bevy});
  baker::writeVolume(smallVolume(*sh), *sh, {directory.path() + "/threejs", baker::VolumeFormat::ThreeJs});
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const baker::fuzz::FuzzDirectory directory("engine-exports");
  static const bool written = writeExports(directory);
  static const char* const kFiles[] = {"bevy/irradiance_volume.ktx2", "bevy/irradiance_volume.json",
                                       "threejs/light_probe_grid.json"};
  if (!written || size == 0 || data[0] > 2) return 0;
  const std::string file = kFiles[data[0]];
  directory.write(file, data + 1, size - 1);
  try {
    baker::readVolume(directory.path() + "/" + file.substr(0, file.find('/')));
  } catch (const baker::InputError&) {
  }
  return 0;
}
