#include "bake/ProbeTracer.h"

#include <algorithm>

#include "scene/Shading.h"

namespace baker {

ProbeTracer::ProbeTracer(const Scene& scene, const RayTracer& tracer, std::vector<Eigen::Vector3f> directions)
    : scene_(scene), tracer_(tracer), directions_(std::move(directions)) {}

void ProbeTracer::trace(const Eigen::Vector3f& position, Eigen::Vector3f* radiance) const {
  Hit hits[8];
  const int n = int(directions_.size());
  for (int first = 0; first < n; first += 8) {
    const int count = std::min(8, n - first);
    tracer_.intersect8(position, directions_.data() + first, count, hits);
    for (int i = 0; i < count; ++i) {
      Eigen::Vector3f& out = radiance[first + i];
      out.setZero();
      const Hit& hit = hits[i];
      if (hit.missed()) continue;
      const SurfaceSample surface = shadeSurface(scene_, scene_.instances[hit.instance].mesh, hit.triangle, hit.u, hit.v);
      if (hit.frontFace || surface.doubleSided) out = surface.emission;
    }
  }
}

}  // namespace baker
