#include "tests/TransportTestSupport.h"

namespace baker::test {

BakedProbe bakeProbe(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                     const Eigen::Vector3f& position) {
  const ProbeBaker probeBaker(scene, tracer, basis, settings, 1);
  BakedProbe out;
  out.coefficients.resize(probeBaker.coefficientsPerProbe());
  out.visibility.resize(probeBaker.visibilityPerProbe());
  std::vector<ProbeSamples> samples;
  probeBaker.bake({{position, 0, 0}}, out.coefficients.data(), out.visibility.data(), &out.rays, &samples);
  out.samples = std::move(samples[0]);
  return out;
}

}  // namespace baker::test
