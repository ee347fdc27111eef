// Relighting at run time (docs/RELIGHTING.md): the sky's SH and irradiance (volume/SkyHarmonics)
// against skies whose SH is known in closed form, and decoders/baker_irradiance.h's relitIrradiance
// against the library's (formats/VolumeReconstruction) for every basis, irradiance and radiance.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "basis/BasisRegistry.h"
#include "decoders/baker_irradiance.h"
#include "formats/VolumeReconstruction.h"
#include "tests/ImporterDecoder.h"
#include "tests/RandomDirection.h"
#include "volume/SkyHarmonics.h"

namespace baker {
namespace {

// A sky L(ω) = a + b·ω_y recorded as a 128 × 64 map (each texel its patch's mean, which for a sky
// linear in ω_y = μ is its value at the patch's mean μ). Its SH, integrated in closed form over
// each patch: L_00 = Σ_rows L_row · 2π(μ0 − μ1)/√(4π), L_1,−1 = Σ_rows L_row · √(3/4π) · π(μ0² − μ1²),
// the rest 0; within 5e-4 of the linear sky's own (a√(4π), b√(4π/3)), the map's resolution.
// E(n) = π L_00 Y_00 + (2π/3) L_1,−1 Y_1,−1(n).
TEST(DecoderRelight, SkyHarmonicsOfALinearSky) {
  const double a = 0.8, b = 0.5;
  SkyRadiance sky;
  double l00 = 0.0, l1 = 0.0;
  for (int row = 0; row < sky.height; ++row) {
    const double mu0 = std::cos(M_PI * row / sky.height), mu1 = std::cos(M_PI * (row + 1) / sky.height);
    const double mean = a + b * 0.5 * (mu0 + mu1);
    l00 += mean * 2.0 * M_PI * (mu0 - mu1) / std::sqrt(4.0 * M_PI);
    l1 += mean * std::sqrt(3.0 / (4.0 * M_PI)) * M_PI * (mu0 * mu0 - mu1 * mu1);
    for (int column = 0; column < sky.width; ++column)
      for (int c = 0; c < 3; ++c) sky.rgb[3 * (std::size_t(row) * sky.width + column) + c] = float(mean * (c + 1));
  }
  EXPECT_NEAR(l1, b * std::sqrt(4.0 * M_PI / 3.0), 5e-4 * l1);
  const SkyHarmonics harmonics = SkyHarmonics::of(sky);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(harmonics.radiance(0, c), (c + 1) * l00, 1e-6);
    EXPECT_NEAR(harmonics.radiance(1, c), (c + 1) * l1, 1e-6);
    for (int k = 2; k < 9; ++k) EXPECT_NEAR(harmonics.radiance(k, c), 0.0, 1e-6) << k;
  }
  std::mt19937 rng(5);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d n = test::randomDirection(rng);
    const Eigen::Vector3d e = harmonics.irradiance(n);
    const double expected = M_PI * l00 / std::sqrt(4.0 * M_PI) + 2.0 * M_PI / 3.0 * l1 * std::sqrt(3.0 / (4.0 * M_PI)) * n.y();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], (c + 1) * expected, 1e-5);
  }
}

baker_decode::Vec3 toDecoder(const Eigen::Vector3d& d) { return {d.x(), d.y(), d.z()}; }

// Random rest coefficients, visibility and sky in [−1, 1]: E reaches some tens, so 1e-5 of
// max(1, |E|) is the bound, as for the other decoders.
TEST(DecoderRelight, HeaderMatchesTheLibrary) {
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  int checked = 0;
  for (const std::string& name : basisNames())
    for (const StoredSignal signal : {StoredSignal::Irradiance, StoredSignal::Radiance}) {
      const VolumeReconstruction library(makeBasis(name), signal);
      const baker_decode::BasisDecoder decoder = test::importerDecoder(library.basis(), signal);
      if (signal == StoredSignal::Radiance && !decoder.decodesRadiance()) continue;
      for (int i = 0; i < 40; ++i) {
        std::vector<float> rest(std::size_t(library.basis().totalCoefficients())),
            visibility(std::size_t(library.basis().functions(0).count())), sky(27);
        for (std::vector<float>* values : {&rest, &visibility, &sky})
          for (float& x : *values) x = uniform(rng);
        SkyHarmonics harmonics;
        for (int k = 0; k < 9; ++k)
          for (int c = 0; c < 3; ++c) harmonics.radiance(k, c) = sky[std::size_t(9 * c + k)];
        const Eigen::Vector3d n = test::randomDirection(rng);
        const Eigen::Vector3f expected = library.relitIrradiance(rest.data(), visibility.data(), n, harmonics);
        const baker_decode::Rgb got =
            signal == StoredSignal::Radiance
                ? decoder.relitIrradianceFromRadiance(rest.data(), visibility.data(), toDecoder(n), sky.data())
                : decoder.relitIrradiance(rest.data(), visibility.data(), toDecoder(n), sky.data());
        const double bound = 1e-5 * std::max(1.0, double(expected.cwiseAbs().maxCoeff()));
        EXPECT_NEAR(got.r, expected.x(), bound) << name;
        EXPECT_NEAR(got.g, expected.y(), bound) << name;
        EXPECT_NEAR(got.b, expected.z(), bound) << name;
        ++checked;
      }
    }
  EXPECT_GT(checked, 40 * 12);
}

}  // namespace
}  // namespace baker
