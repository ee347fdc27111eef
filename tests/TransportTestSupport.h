#pragma once
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "bake/Basis.h"
#include "bake/ProbeBaker.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker::test {

// One probe baked in-process, as `baker probe` does: its samples and its coefficients.
struct BakedProbe {
  ProbeSamples samples;
  std::vector<float> coefficients;
  std::vector<float> visibility;
  RayCounts rays;
};

BakedProbe bakeProbe(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                     const Eigen::Vector3f& position);

}  // namespace baker::test
