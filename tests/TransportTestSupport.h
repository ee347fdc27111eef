#pragma once
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "bake/ProbeBaker.h"
#include "basis/Basis.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker::test {

// A scene and its BVH, owned together (the tracer refers to the scene): what a test traces.
class TracedScene {
 public:
  explicit TracedScene(Scene scene, bool alphaFilters = true)
      : scene_(std::make_unique<Scene>(std::move(scene))), tracer_(std::make_unique<RayTracer>(*scene_, alphaFilters)) {}
  const Scene& scene() const { return *scene_; }
  const RayTracer& tracer() const { return *tracer_; }

 private:
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<RayTracer> tracer_;
};

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
