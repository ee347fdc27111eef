#pragma once
#include <tiny_gltf.h>

#include <optional>
#include <string>
#include <vector>

#include "scene/ColorImage.h"

namespace baker {

// The encoded bytes of the glTF images, captured through tinygltf's image callback while it
// loads (so tinygltf decodes nothing) and decoded later, once, only for images a material uses.
class GltfImages {
 public:
  // Routes `loader`'s images here; this object must outlive the load.
  void install(tinygltf::TinyGLTF& loader);

  // images[index] decoded, or nothing plus a warning naming the file and the image when a user
  // would rather go on (its file is missing, it is not a PNG or JPEG, it does not decode):
  // materials then use their factors alone. A bufferView outside its buffer is an InputError.
  std::optional<ColorImage> decode(const tinygltf::Model& model, int index, const std::string& file,
                                   std::vector<std::string>& warnings) const;

 private:
  static bool capture(tinygltf::Image* image, int index, std::string* err, std::string* warn, int, int,
                      const unsigned char* bytes, int size, void* self);

  std::vector<std::vector<unsigned char>> captured_;  // by image index; bufferView images stay empty
};

}  // namespace baker
