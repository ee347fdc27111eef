#include "scene/Shading.h"

namespace baker {
namespace {

template <typename T>
T interpolate(const SurfacePoint& p, const std::vector<T>& attribute) {
  const Eigen::Vector3i& c = *p.corners;
  return p.w0 * attribute[c[0]] + p.w1 * attribute[c[1]] + p.w2 * attribute[c[2]];
}

// Where `slot`'s texture is read at the point: its coordinates after KHR_texture_transform,
// wrapped onto texels.
ColorImage::Footprint texelsOf(const ColorImage& image, const TextureSlot& slot, const SurfacePoint& p) {
  const auto& sets = p.mesh->texcoords;
  const Eigen::Vector2f uv = std::size_t(slot.texCoord) < sets.size() && !sets[slot.texCoord].empty()
                                 ? interpolate(p, sets[slot.texCoord])
                                 : Eigen::Vector2f::Zero();
  // Written out: Eigen's product with uv.homogeneous() is not inlined, and costs more than this.
  // It adds in the same order, (m00·u + m01·v) + m02, so textures read the same texels.
  const Eigen::Matrix<float, 2, 3>& m = slot.uvTransform;
  return image.footprint({m(0, 0) * uv.x() + m(0, 1) * uv.y() + m(0, 2), m(1, 0) * uv.x() + m(1, 1) * uv.y() + m(1, 2)},
                         slot.sampler);
}

Eigen::Vector4f baseColor(const SurfacePoint& p) {
  Eigen::Vector4f c = p.material->baseColor;
  if (p.baseColorImage) c = c.cwiseProduct(p.baseColorImage->sample(p.baseColorTexels));
  if (!p.mesh->colors.empty()) c = c.cwiseProduct(interpolate(p, p.mesh->colors));
  return c;
}

}  // namespace

void locateTexels(SurfacePoint* point) {
  SurfacePoint& p = *point;
  const Material& m = *p.material;
  if (p.baseColorImage) p.baseColorTexels = texelsOf(*p.baseColorImage, m.baseColorTexture, p);
  if (p.emissiveImage) p.emissiveTexels = texelsOf(*p.emissiveImage, m.emissiveTexture, p);
}

void prefetchSurface(const SurfacePoint& p) {
  if (p.baseColorImage) p.baseColorImage->prefetch(p.baseColorTexels);
  if (p.emissiveImage) p.emissiveImage->prefetch(p.emissiveTexels);
}

Eigen::Vector3f variedAlbedo(const SurfacePoint& p) { return baseColor(p).head<3>(); }

Eigen::Vector3f surfaceEmission(const SurfacePoint& p) {
  if (!p.emissiveImage) return p.material->emission;
  return p.material->emission.cwiseProduct(p.emissiveImage->sample(p.emissiveTexels).head<3>());
}

SurfaceSample shadeSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v) {
  SurfacePoint p;
  locateSurface(scene, mesh, triangle, u, v, &p);
  const Eigen::Vector4f base = baseColor(p);
  SurfaceSample s;
  s.albedo = base.head<3>();
  s.alpha = p.material->alphaTested() ? base.w() : 1.0f;
  s.emission = surfaceEmission(p);
  s.doubleSided = p.material->doubleSided;
  return s;
}

bool surfaceStopsRay(const SurfacePoint& p, float xi) {
  const Material& material = *p.material;
  if (!material.alphaTested()) return true;
  const float alpha = baseColor(p).w();
  return material.alphaMode == AlphaMode::Mask ? alpha >= material.alphaCutoff : xi < alpha;
}

bool surfaceStopsRay(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v, float xi) {
  const Material& material = scene.materials[scene.meshes[mesh].triangleMaterial[triangle]];
  if (!material.alphaTested()) return true;
  SurfacePoint p;
  locateSurface(scene, mesh, triangle, u, v, &p);
  return surfaceStopsRay(p, xi);
}

}  // namespace baker
