#include "scene/SceneCensus.h"

namespace baker {

SceneCensus takeCensus(const Scene& scene) {
  SceneCensus c;
  c.materialInUse.assign(scene.materials.size(), false);
  // Triangles per material per mesh, then multiplied by the mesh's instance count.
  std::vector<std::uint64_t> uses(scene.meshes.size(), 0);
  for (const Instance& instance : scene.instances) ++uses[instance.mesh];
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    c.uniqueTriangles += mesh.triangleCount();
    if (uses[m] > 1) ++c.instancedMeshes;
    for (std::uint32_t material : mesh.triangleMaterial) {
      const Material& mat = scene.materials[material];
      if (uses[m] > 0) c.materialInUse[material] = true;
      c.triangles += uses[m];
      if (mat.emissive()) c.emissiveTriangles += uses[m];
      if (mat.reflective()) c.reflectiveTriangles += uses[m];
      if (mat.alphaTested()) c.alphaTestedTriangles += uses[m];
    }
  }
  for (bool used : c.materialInUse) c.materialsInUse += used;
  // The last material is the loader's stand-in for primitives without one, not the file's.
  for (std::size_t i = 0; i + 1 < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    ++c.materialsByAlphaMode[int(m.alphaMode)];
    c.doubleSidedMaterials += m.doubleSided;
    c.texturedMaterials += m.baseColorTexture.present() || m.emissiveTexture.present();
  }
  for (const PunctualLight& light : scene.lights) ++c.lightsByType[int(light.type)];
  for (const ColorImage& image : scene.images) {
    c.textureTexels += std::uint64_t(image.width()) * image.height();
    c.textureBytes += image.memoryBytes();
  }
  return c;
}

}  // namespace baker
