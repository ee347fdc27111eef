#pragma once
#include <Eigen/Core>
#include <string>

#include "scene/ColorImage.h"

namespace baker {

enum class AlphaMode { Opaque, Mask, Blend };

// A texture as one material slot uses it: the decoded image, how it is sampled, which UV set
// it reads, and the KHR_texture_transform applied to those UVs (uv' = uvTransform · (u, v, 1)).
struct TextureSlot {
  int image = -1;  // index into Scene::images; -1: no texture, the factor alone
  SamplerState sampler;
  int texCoord = 0;
  Eigen::Matrix<float, 2, 3> uvTransform = Eigen::Matrix<float, 2, 3>::Identity();

  bool present() const { return image >= 0; }
};

// What a glTF material means for diffuse light transport. Metallic, roughness, normal maps and
// the like do not change a Lambertian bake and are not kept.
struct Material {
  std::string name;
  Eigen::Vector4f baseColor{1.0f, 1.0f, 1.0f, 1.0f};  // baseColorFactor, alpha in w
  TextureSlot baseColorTexture;
  // Emitted radiance factor: emissiveFactor × KHR_materials_emissive_strength.
  Eigen::Vector3f emission{0.0f, 0.0f, 0.0f};
  TextureSlot emissiveTexture;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;

  // MASK and BLEND surfaces let some rays through, so their geometry needs Embree filters.
  bool alphaTested() const { return alphaMode != AlphaMode::Opaque; }
  bool emissive() const { return emission.maxCoeff() > 0.0f; }
  // A texture can only darken the factor, so a zero factor means no reflection at all.
  bool reflective() const { return baseColor.head<3>().maxCoeff() > 0.0f; }
};

}  // namespace baker
