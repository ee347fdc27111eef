// decoders/baker_irradiance.h on radiance volumes: irradiance, visibility and glossy specular
// against the library, and the closed-form lobe responses it carries against the library's
// series, which is computed by quadrature (basis/LegendreResponse.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "basis/BasisRegistry.h"
#include "basis/SpecularBlend.h"
#include "decoders/baker_irradiance.h"
#include "formats/ReconstructionData.h"
#include "formats/VolumeReconstruction.h"
#include "tests/ImporterDecoder.h"
#include "tests/RandomDirection.h"

namespace baker {
namespace {

using nlohmann::json;

constexpr unsigned kSeed = 20261205;

using test::randomDirection;

baker_decode::Vec3 toDecoder(const Eigen::Vector3d& d) { return {d.x(), d.y(), d.z()}; }

// The decoder as an importer builds it for a radiance volume; every radial basis takes its
// diffuse response.
baker_decode::BasisDecoder radianceDecoder(const Basis& basis) {
  baker_decode::BasisDecoder decoder = test::importerDecoder(basis, StoredSignal::Radiance);
  EXPECT_TRUE(decoder.decodesRadiance()) << basis.name();
  return decoder;
}

baker_decode::SpecularTable specularTable(const Basis& basis) {
  const json blend = specularBlendOf(basis)->describe();
  baker_decode::SpecularTable table;
  for (int j = 0; j < baker_decode::SpecularTable::kSteps; ++j)
    for (int k = 0; k < baker_decode::SpecularTable::kSteps; ++k) {
      table.diffuseWeight[j][k] = blend["diffuse_weight"][j][k].get<double>();
      table.albedo[j][k] = blend["albedo"][j][k].get<double>();
    }
  return table;
}

void expectRgbNear(const baker_decode::Rgb& got, const Eigen::Vector3f& expected, double tolerance, const std::string& what) {
  EXPECT_NEAR(got.r, expected.x(), tolerance) << what;
  EXPECT_NEAR(got.g, expected.y(), tolerance) << what;
  EXPECT_NEAR(got.b, expected.z(), tolerance) << what;
}

const std::vector<std::string> kRadialBases = {"sh-l1",        "sh-l2", "sh-l4", "ad-cos2", "ad-srbf",
                                               "ambient-cube", "sg-9",  "sg-12", "ad-hemi9"};

// ad-hemi9 about axes other than +Y: a wall's, the floor's from above (−Y, the half-turn case)
// and an oblique one. Its decoder takes the axes from the file.
std::vector<std::unique_ptr<Basis>> turnedHemispheres() {
  std::vector<std::unique_ptr<Basis>> bases;
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0.3, -0.5, 0.8)})
    bases.push_back(makeBasis("ad-hemi9", {std::nullopt, axis}));
  return bases;
}

std::vector<std::unique_ptr<Basis>> radialBases() {
  std::vector<std::unique_ptr<Basis>> bases = turnedHemispheres();
  for (const std::string& name : kRadialBases) bases.push_back(makeBasis(name));
  return bases;
}

// Coefficients in [0, 1] (a radiance fit's scale): E reaches some π, so 1e-5 of it is the bound.
TEST(DecoderRadiance, IrradianceAndVisibilityMatchTheLibrary) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (const std::unique_ptr<Basis>& basis : radialBases()) {
    const std::string name = basis->identity();
    const VolumeReconstruction library(makeBasisLike(*basis), StoredSignal::Radiance);
    const baker_decode::BasisDecoder decoder = radianceDecoder(library.basis());
    ASSERT_TRUE(decoder.decodesRadiance()) << name;
    for (int n = 0; n < 200; ++n) {
      std::vector<float> c(std::size_t(library.basis().totalCoefficients()));
      for (float& x : c) x = uniform(rng);
      const Eigen::Vector3d d = randomDirection(rng);
      expectRgbNear(decoder.irradianceFromRadiance(c.data(), toDecoder(d)), library.irradiance(c.data(), d), 1e-5 * M_PI, name);
      expectRgbNear(decoder.radiance(c.data(), toDecoder(d)), library.radiance(c.data(), d), 1e-5, name);
      EXPECT_NEAR(decoder.visibilityFromRadiance(c.data(), toDecoder(d)), library.skyVisibility(c.data(), d), 1e-5) << name;
    }
  }
}

TEST(DecoderRadiance, SpecularMatchesTheLibrary) {
  std::mt19937 rng(kSeed + 1);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<std::unique_ptr<Basis>> bases = turnedHemispheres();
  for (const std::string& name : {"sh-l2", "ad-srbf", "ambient-cube", "sg-12", "ad-hemi9"}) bases.push_back(makeBasis(name));
  for (const std::unique_ptr<Basis>& basis : bases) {
    const std::string name = basis->identity();
    const VolumeReconstruction library(makeBasisLike(*basis), StoredSignal::Radiance);
    const baker_decode::BasisDecoder decoder = radianceDecoder(library.basis());
    const baker_decode::SpecularTable table = specularTable(library.basis());
    for (double roughness : {0.0, 0.1, 0.37, 0.6, 1.0}) {
      for (int n = 0; n < 60; ++n) {
        std::vector<float> c(std::size_t(library.basis().totalCoefficients()));
        for (float& x : c) x = uniform(rng);
        const Eigen::Vector3d normal = randomDirection(rng);
        // Views from every side: grazing and below the surface are clamped alike by both.
        const Eigen::Vector3d view = n == 0 ? normal : n == 1 ? Eigen::Vector3d(-normal) : randomDirection(rng);
        const VolumeReconstruction::Specular expected = library.specular(c.data(), normal, view, roughness);
        const baker_decode::Specular got = decoder.specular(c.data(), toDecoder(normal), toDecoder(view), roughness, table);
        const std::string what = name + " roughness " + std::to_string(roughness);
        expectRgbNear(got.value, expected.value, 1e-5, what);
        EXPECT_NEAR(got.diffuseWeight, expected.diffuseWeight, 1e-12) << what;
        EXPECT_NEAR(got.albedo, expected.albedo, 1e-12) << what;
      }
    }
  }
}

// The header's responses of the fixed lobes are derived by hand (docs/DECODERS.md): the
// library's series, integrated numerically, must be the same numbers.
TEST(DecoderRadiance, BuiltInLobeResponsesAreTheFilesSeries) {
  for (const std::string& name : {"ad-cos2", "ad-srbf", "ambient-cube", "ad-hemi9"}) {
    const json response = reconstructionData(*makeBasis(name), StoredSignal::Radiance)["function_sets"][0]["diffuse_response"];
    const std::vector<double> series = response["coefficients"].get<std::vector<double>>();
    const baker_decode::BasisDecoder decoder(name.c_str());
    const baker_decode::FunctionSet& set = decoder.functions(0);
    ASSERT_GE(set.responseTerms, int(series.size())) << name;
    for (int l = 0; l < set.responseTerms; ++l)
      EXPECT_NEAR(set.response[l], l < int(series.size()) ? series[std::size_t(l)] : 0.0, 1e-12) << name << " l " << l;
  }
}

// The header turns the icosahedron itself: its axes are the file's.
TEST(DecoderRadiance, HemisphereAxesAreTheFiles) {
  const json set = reconstructionData(*makeBasis("ad-hemi9"), StoredSignal::Radiance)["function_sets"][0];
  const baker_decode::BasisDecoder decoder("ad-hemi9");
  const baker_decode::FunctionSet& functions = decoder.functions(0);
  ASSERT_EQ(functions.count(), 9);
  ASSERT_EQ(set["axes"].size(), 9u);
  for (int i = 0; i < 9; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(functions.axes[3 * i + k], set["axes"][i][k].get<double>(), 1e-12) << i;
}

TEST(DecoderRadiance, PiecewiseVariantsAreRefused) {
  for (const std::string& name : {"ad-linear", "ad-rgb", "ad-rgb-flat", "ad-ycocg"}) {
    baker_decode::BasisDecoder decoder(name.c_str());
    EXPECT_FALSE(decoder.decodesRadiance()) << name;
    const double series[3] = {1.0, 0.0, 0.0};
    EXPECT_FALSE(decoder.setDiffuseResponse(series, 3)) << name;
    const json data = reconstructionData(*makeBasis(name), StoredSignal::Radiance);
    for (const json& set : data["function_sets"]) EXPECT_TRUE(set["diffuse_response"].is_null()) << name;
  }
  EXPECT_FALSE(baker_decode::BasisDecoder("sg-12", 2.0).decodesRadiance()) << "sg-N needs the file's series";
  EXPECT_FALSE(reconstructionData(*makeBasis("sh-l2"), StoredSignal::Irradiance)["function_sets"][0].contains("diffuse_response"));
}

}  // namespace
}  // namespace baker
