#include "scene/Scene.h"

namespace baker {

std::uint64_t Scene::triangleCount() const {
  std::uint64_t total = 0;
  for (const Instance& instance : instances) total += meshes[instance.mesh].triangleCount();
  return total;
}

Eigen::Vector3f Scene::frontNormal(std::uint32_t instance, std::uint32_t triangle) const {
  const Instance& inst = instances[instance];
  const Mesh& mesh = meshes[inst.mesh];
  const Eigen::Vector3i& t = mesh.triangles[triangle];
  const Eigen::Vector3f& p0 = mesh.positions[t[0]];
  const Eigen::Vector3f n = (mesh.positions[t[1]] - p0).cross(mesh.positions[t[2]] - p0);
  return (inst.normalToWorld * n).normalized();
}

}  // namespace baker
