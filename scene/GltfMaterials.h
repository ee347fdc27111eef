#pragma once
#include <tiny_gltf.h>

#include <set>
#include <string>
#include <vector>

#include "scene/ColorImage.h"
#include "scene/GltfImages.h"
#include "scene/Material.h"

namespace baker {

struct GltfMaterials {
  std::vector<Material> materials;  // glTF order, then the glTF default material
  std::uint32_t defaultMaterial = 0;
  std::vector<ColorImage> images;   // the decoded images TextureSlot::image refers to
  std::set<int> texcoordSets;       // the TEXCOORD_n sets some texture reads
};

// Reads every material: base colour and emissive factors and textures (with samplers, texCoord
// sets and KHR_texture_transform), KHR_materials_emissive_strength, alpha mode and cutoff,
// doubleSided. Each image a material uses is decoded once. Malformed values are InputErrors
// naming the glTF path; a texture that cannot be read is a warning and the factor stands alone.
GltfMaterials readMaterials(const tinygltf::Model& model, const GltfImages& images, const std::string& file,
                            std::vector<std::string>& warnings);

}  // namespace baker
