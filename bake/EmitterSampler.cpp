#include "bake/EmitterSampler.h"

#include <algorithm>

#include "scene/Environment.h"

namespace baker {
namespace {

// Up to this many emitters, sample() searches all their running sums: three steps at most.
constexpr std::size_t kSearchedWhole = 8;

}  // namespace

EmitterSampler::EmitterSampler(const Scene& scene) : scene_(scene) {
  double total = 0.0;
  for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[instance.mesh];
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const Material& material = scene.materials[mesh.triangleMaterial[t]];
      if (!material.emissive()) continue;
      const Eigen::Vector3i& c = mesh.triangles[t];
      auto world = [&](int k) -> Eigen::Vector3f {
        return (instance.objectToWorld * mesh.positions[c[k]].homogeneous()).head<3>();
      };
      const Eigen::Vector3f p0 = world(0), e1 = world(1) - p0, e2 = world(2) - p0;
      const float area = 0.5f * e1.cross(e2).norm();
      const double power = double(area) * luminance(material.emission) * (material.doubleSided ? 2.0 : 1.0);
      if (!(area > 0.0f) || !(power > 0.0)) continue;
      emitters_.push_back({scene.globalTriangle(i, t), t, instance.mesh, p0, e1, e2, scene.frontNormal(i, t),
                           material.emission, area, float(power), material.doubleSided,
                           material.emissiveTexture.present(), material.alphaTested()});
      total += power;
    }
  }
  // Instances are numbered in order and their triangles follow each other, so the list is
  // already sorted by global triangle.
  double running = 0.0;
  for (Emitter& e : emitters_) {
    const double p = double(e.pdfArea) / total;  // pdfArea held the power until here
    e.pdfArea = float(p) / e.area;
    running += p;
    cumulative_.push_back(running);
  }
  if (cumulative_.empty()) return;
  cumulative_.back() = 1.0;
  if (cumulative_.size() <= kSearchedWhole) return;
  const std::size_t buckets = cumulative_.size();
  guide_.assign(buckets + 1, 0);
  std::size_t below = 0;
  for (std::size_t j = 0; j <= buckets; ++j) {
    while (below < cumulative_.size() && bucketOf(cumulative_[below], buckets) < j) ++below;
    guide_[j] = std::min(below, buckets - 1);  // no number lies past the last sum, 1
  }
}

float EmitterSampler::pdfArea(std::uint32_t instance, std::uint32_t triangle) const {
  const std::uint64_t id = scene_.globalTriangle(instance, triangle);
  const auto it = std::lower_bound(emitters_.begin(), emitters_.end(), id,
                                   [](const Emitter& e, std::uint64_t g) { return e.globalTriangle < g; });
  return it != emitters_.end() && it->globalTriangle == id ? it->pdfArea : 0.0f;
}

}  // namespace baker
