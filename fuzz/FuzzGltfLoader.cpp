// libFuzzer target: the glTF loader on any bytes, as a .glb when they start with the binary
// magic "glTF" and as a .gltf otherwise. An input must load or stop with InputError; a crash,
// a sanitizer report, any other exception, a hang or an allocation beyond libFuzzer's limit is
// a finding.
#include <cstring>

#include "common/Error.h"
#include "fuzz/FuzzFiles.h"
#include "scene/GltfLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const baker::fuzz::FuzzDirectory directory("gltf");
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = directory.write(binary ? "scene.glb" : "scene.gltf", data, size);
  try {
    baker::loadGltf(path);
  } catch (const baker::InputError&) {
  }
  return 0;
}
