// libFuzzer target: the volume reader on any bytes written as a .vdb file. An input must read
// or stop with InputError; anything else is a finding.
#include "common/Error.h"
#include "formats/VolumeReader.h"
#include "fuzz/FuzzFiles.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const baker::fuzz::FuzzDirectory directory("vdb");
  const std::string path = directory.write("volume.vdb", data, size);
  try {
    baker::readVolume(path);
  } catch (const baker::InputError&) {
  }
  return 0;
}
