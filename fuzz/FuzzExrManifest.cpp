// libFuzzer target: the EXR-slices reader on any bytes as manifest.json, beside the slices of
// a small valid volume (2 × 2 × 2 probes of sh-l1 with visibility and probe states) written
// once per process. The manifest is what a reader trusts to find, size and name everything
// else, so it is what is fuzzed; the slices are OpenEXR's to parse. An input must read or stop
// with InputError; anything else is a finding.
#include <filesystem>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/ExrSlices.h"
#include "formats/VolumeReader.h"
#include "fuzz/FuzzFiles.h"

namespace {

std::string writeSlices(const baker::fuzz::FuzzDirectory& directory) {
  const std::unique_ptr<baker::Basis> basis = baker::makeBasis("sh-l1");
  baker::Volume volume;
  volume.grid.dims = {2, 2, 2};
  volume.basisName = basis->name();
  volume.coefficientsPerProbe = basis->totalCoefficients();
  volume.visibilityPerProbe = basis->functions(0).count();
  const std::size_t probes = std::size_t(volume.grid.probeCount());
  volume.coefficients.assign(probes * volume.coefficientsPerProbe, 0.5f);
  volume.visibility.assign(probes * volume.visibilityPerProbe, 1.0f);
  volume.states.assign(probes, baker::ProbeState::Valid);
  volume.offsets.assign(probes, Eigen::Vector3f::Zero());
  const std::string path = directory.path() + "/volume";
  baker::writeExrSlices(volume, *basis, path, baker::ExrPrecision::Half);
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const baker::fuzz::FuzzDirectory directory("exr-manifest");
  static const std::string volume = writeSlices(directory);
  directory.write("volume/manifest.json", data, size);
  try {
    baker::readVolume(volume);
  } catch (const baker::InputError&) {
  }
  return 0;
}
