#include "tests/TransportTestSupport.h"

#include "bake/ProbesAt.h"

namespace baker::test {

BakedProbe bakeProbe(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                     const Eigen::Vector3f& position) {
  BakedProbes baked = bakeTasks(scene, tracer, basis, settings, {{position, 0, 0}});
  return {std::move(baked.samples[0]), std::move(baked.coefficients), std::move(baked.visibility), baked.rays};
}

}  // namespace baker::test
