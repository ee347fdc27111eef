#include <gtest/gtest.h>

#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

class ProjectionOptionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    room_ = std::make_unique<test::TracedScene>(loadGltf(test::sourcePath("data/default_room/default_room.gltf")));
    grid_ = makeProbeGrid(room_->scene().bounds, 1.0, 1000);
  }
  Volume bake(const std::string& basisName, const ProjectionOptions& options) {
    BakeSettings settings;
    settings.projection = options;
    return bakeVolume(room_->scene(), room_->tracer(), *makeBasis(basisName), grid_, settings, nullptr);
  }
  std::unique_ptr<test::TracedScene> room_;
  ProbeGrid grid_;
};

// For orthonormal SH the window multiplies band l of every coefficient by h_l exactly.
TEST_F(ProjectionOptionsTest, WindowScalesEachShBandByItsFactor) {
  const Volume plain = bake("sh-l2", {});
  ProjectionOptions windowed;
  windowed.window.hannWidth = 2;  // h = 1, 0.75, 0.25
  const Volume faded = bake("sh-l2", windowed);
  ASSERT_EQ(plain.coefficients.size(), faded.coefficients.size());
  int compared = 0;
  for (std::int64_t p = 0; p < plain.grid.probeCount(); ++p)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l <= 2; ++l)
        for (int m = -l; m <= l; ++m) {
          const int i = c * 9 + l * l + l + m;
          const float expected = plain.probe(p)[i] * float(windowed.window.factor(l));
          EXPECT_NEAR(faded.probe(p)[i], expected, 1e-5f * (1.0f + std::abs(plain.probe(p)[i])));
          ++compared;
        }
  EXPECT_GT(compared, 100);
}

// A room lit by one small panel makes the linear ad-srbf projection ring below zero in some
// probes; the constrained solve must leave every coefficient at or above zero.
TEST_F(ProjectionOptionsTest, NonNegativeRemovesNegativeCoefficients) {
  const Volume linear = bake("ad-srbf", {});
  ProjectionOptions constrained;
  constrained.nonNegative = true;
  const Volume clamped = bake("ad-srbf", constrained);
  const float mostNegativeLinear = *std::min_element(linear.coefficients.begin(), linear.coefficients.end());
  const float mostNegativeConstrained = *std::min_element(clamped.coefficients.begin(), clamped.coefficients.end());
  EXPECT_LT(mostNegativeLinear, 0.0f) << "the scene no longer exercises the constraint";
  EXPECT_GE(mostNegativeConstrained, 0.0f);
}

}  // namespace
}  // namespace baker
