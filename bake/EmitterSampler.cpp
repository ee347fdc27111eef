#include "bake/EmitterSampler.h"

#include <algorithm>
#include <cmath>

#include "scene/Environment.h"

namespace baker {

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
  if (!cumulative_.empty()) cumulative_.back() = 1.0;
}

EmitterSampler::Sample EmitterSampler::sample(float xiChoice, float xi1, float xi2) const {
  // std::upper_bound without branches: its comparisons go either way at random, and each
  // mispredicted one costs more than the comparison.
  const double x = xiChoice;
  const double* first = cumulative_.data();
  for (std::size_t length = cumulative_.size(); length > 1;) {
    const std::size_t half = length / 2;
    first += (first[half - 1] <= x) ? half : 0;
    length -= half;
  }
  const std::size_t index = std::size_t(first - cumulative_.data()) + (*first <= x ? 1 : 0);
  const Emitter& e = emitters_[std::min(index, emitters_.size() - 1)];
  // Uniform on the triangle: the square-root warp of the unit square.
  const float s = std::sqrt(xi1);
  const float u = s * (1.0f - xi2), v = s * xi2;
  return {e.p0 + u * e.e1 + v * e.e2, u, v, &e};
}

float EmitterSampler::pdfArea(std::uint32_t instance, std::uint32_t triangle) const {
  const std::uint64_t id = scene_.globalTriangle(instance, triangle);
  const auto it = std::lower_bound(emitters_.begin(), emitters_.end(), id,
                                   [](const Emitter& e, std::uint64_t g) { return e.globalTriangle < g; });
  return it != emitters_.end() && it->globalTriangle == id ? it->pdfArea : 0.0f;
}

}  // namespace baker
