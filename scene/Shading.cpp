#include "scene/Shading.h"

namespace baker {
namespace {

// A point of a triangle: its corners and their barycentric weights.
struct TrianglePoint {
  const Mesh& mesh;
  const Eigen::Vector3i& corners;
  float w0, w1, w2;

  template <typename T>
  T interpolate(const std::vector<T>& attribute) const {
    return w0 * attribute[corners[0]] + w1 * attribute[corners[1]] + w2 * attribute[corners[2]];
  }
};

TrianglePoint pointOf(const Mesh& mesh, std::uint32_t triangle, float u, float v) {
  return {mesh, mesh.triangles[triangle], 1.0f - u - v, u, v};
}

// The texture coordinates `slot` reads at the point, after its KHR_texture_transform.
Eigen::Vector2f texCoords(const TextureSlot& slot, const TrianglePoint& p) {
  const auto& sets = p.mesh.texcoords;
  const Eigen::Vector2f uv = std::size_t(slot.texCoord) < sets.size() && !sets[slot.texCoord].empty()
                                 ? p.interpolate(sets[slot.texCoord])
                                 : Eigen::Vector2f::Zero();
  return slot.uvTransform * uv.homogeneous();
}

Eigen::Vector4f lookup(const Scene& scene, const TextureSlot& slot, const TrianglePoint& p) {
  return scene.images[slot.image].sample(texCoords(slot, p), slot.sampler);
}

Eigen::Vector4f baseColor(const Scene& scene, const Material& m, const TrianglePoint& p) {
  Eigen::Vector4f c = m.baseColor;
  if (m.baseColorTexture.present()) c = c.cwiseProduct(lookup(scene, m.baseColorTexture, p));
  if (!p.mesh.colors.empty()) c = c.cwiseProduct(p.interpolate(p.mesh.colors));
  return c;
}

Eigen::Vector3f emission(const Scene& scene, const Material& m, const TrianglePoint& p) {
  if (!m.emissiveTexture.present() || !m.emissive()) return m.emission;
  return m.emission.cwiseProduct(lookup(scene, m.emissiveTexture, p).head<3>());
}

}  // namespace

SurfaceSample shadeSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v) {
  const Mesh& m = scene.meshes[mesh];
  const Material& material = scene.materials[m.triangleMaterial[triangle]];
  const TrianglePoint p = pointOf(m, triangle, u, v);
  const Eigen::Vector4f base = baseColor(scene, material, p);
  SurfaceSample s;
  s.albedo = base.head<3>();
  s.alpha = material.alphaTested() ? base.w() : 1.0f;
  s.emission = emission(scene, material, p);
  s.doubleSided = material.doubleSided;
  return s;
}

Eigen::Vector3f surfaceAlbedo(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v) {
  const Mesh& m = scene.meshes[mesh];
  return baseColor(scene, scene.materials[m.triangleMaterial[triangle]], pointOf(m, triangle, u, v)).head<3>();
}

Eigen::Vector3f surfaceEmission(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v) {
  const Mesh& m = scene.meshes[mesh];
  return emission(scene, scene.materials[m.triangleMaterial[triangle]], pointOf(m, triangle, u, v));
}

void prefetchSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v) {
  const Mesh& m = scene.meshes[mesh];
  const Material& material = scene.materials[m.triangleMaterial[triangle]];
  const TrianglePoint p = pointOf(m, triangle, u, v);
  if (material.baseColorTexture.present())
    scene.images[material.baseColorTexture.image].prefetch(texCoords(material.baseColorTexture, p),
                                                           material.baseColorTexture.sampler);
  if (material.emissiveTexture.present() && material.emissive())
    scene.images[material.emissiveTexture.image].prefetch(texCoords(material.emissiveTexture, p),
                                                          material.emissiveTexture.sampler);
}

bool surfaceStopsRay(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v, float xi) {
  const Mesh& m = scene.meshes[mesh];
  const Material& material = scene.materials[m.triangleMaterial[triangle]];
  if (!material.alphaTested()) return true;
  const float alpha = baseColor(scene, material, pointOf(m, triangle, u, v)).w();
  return material.alphaMode == AlphaMode::Mask ? alpha >= material.alphaCutoff : xi < alpha;
}

}  // namespace baker
