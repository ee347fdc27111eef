#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "basis/BasisRegistry.h"
#include "basis/Icosahedron.h"
#include "basis/ShBasis.h"
#include "decoders/baker_irradiance.h"
#include "formats/ReconstructionData.h"
#include "tests/RandomDirection.h"

namespace baker {
namespace {

using nlohmann::json;

constexpr unsigned kSeed = 20240611;
constexpr int kDirections = 300;

using test::randomDirection;

std::vector<float> randomCoefficients(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> c(count);
  for (float& x : c) x = uniform(rng);
  return c;
}

baker_decode::Vec3 toDecoder(const Eigen::Vector3d& d) { return {d.x(), d.y(), d.z()}; }
Eigen::Vector3d fromJson(const json& d) { return {d[0].get<double>(), d[1].get<double>(), d[2].get<double>()}; }

// The header's decoder as an importer builds it: the name from "baker.basis" and, for sg-N, the
// sharpness and axes from "baker.reconstruction".
baker_decode::BasisDecoder importerDecoder(const Basis& basis) {
  const json data = reconstructionData(basis, StoredSignal::Irradiance);
  const json& set = data["function_sets"][0];
  if (set["type"] != "spherical-gaussians") return baker_decode::BasisDecoder(basis.name().c_str());
  baker_decode::BasisDecoder decoder(basis.name().c_str(), set["sharpness"].get<double>());
  std::vector<double> axes;
  for (const json& axis : set["axes"])
    for (int k = 0; k < 3; ++k) axes.push_back(axis[k].get<double>());
  decoder.setLobeAxes(axes.data());
  return decoder;
}

// The header against Basis::reconstruct, within 1e-5 of the coefficients' magnitude (≤ 1).
void expectHeaderMatchesLibrary(const Basis& basis, const baker_decode::BasisDecoder& decoder) {
  ASSERT_TRUE(decoder.valid()) << basis.name();
  ASSERT_EQ(decoder.coefficientsPerProbe(), basis.totalCoefficients()) << basis.name();
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(decoder.coefficientCount(c), basis.coefficientCount(c)) << basis.name();
    EXPECT_EQ(decoder.coefficientOffset(c), basis.coefficientOffset(c)) << basis.name();
  }
  // Random directions, after the icosahedron's vertices and the axes, where triangle and
  // octant lookups are at their edges.
  std::vector<Eigen::Vector3d> directions;
  for (int i = 0; i < Icosahedron::kVertexCount; ++i) directions.push_back(Icosahedron::instance().vertex(i));
  for (int axis = 0; axis < 3; ++axis) {
    directions.push_back(Eigen::Vector3d::Unit(axis));
    directions.push_back(-Eigen::Vector3d::Unit(axis));
  }
  std::mt19937 rng(kSeed);
  while (int(directions.size()) < kDirections) directions.push_back(randomDirection(rng));
  for (const Eigen::Vector3d& d : directions) {
    const std::vector<float> c = randomCoefficients(rng, basis.totalCoefficients());
    const Eigen::Vector3f expected = basis.reconstruct(c.data(), d);
    const baker_decode::Rgb got = decoder.irradiance(c.data(), toDecoder(d));
    EXPECT_NEAR(got.r, expected.x(), 1e-5) << basis.name() << " direction " << d.transpose();
    EXPECT_NEAR(got.g, expected.y(), 1e-5) << basis.name() << " direction " << d.transpose();
    EXPECT_NEAR(got.b, expected.z(), 1e-5) << basis.name() << " direction " << d.transpose();
  }
}

TEST(DecoderHeader, MatchesTheLibraryForEveryBasis) {
  for (const std::string& name : basisNames()) expectHeaderMatchesLibrary(*makeBasis(name), importerDecoder(*makeBasis(name)));
}

// The registry stops at sh-l8; the header covers every order SphericalHarmonics supports.
TEST(DecoderHeader, MatchesTheLibraryForHighShOrders) {
  for (int order : {9, 16, 40, SphericalHarmonics::kMaxOrder}) {
    const ShBasis basis(order);
    expectHeaderMatchesLibrary(basis, baker_decode::BasisDecoder(basis.name().c_str()));
  }
}

TEST(DecoderHeader, UsesTheSgSharpnessAndAxesOfTheMetadata) {
  for (const std::string& name : {"sg-5", "sg-9", "sg-64"}) {
    const auto basis = makeBasis(name, {1.7});
    expectHeaderMatchesLibrary(*basis, importerDecoder(*basis));
  }
  EXPECT_FALSE(baker_decode::BasisDecoder("sg-9").valid()) << "sg-N needs its sharpness";
}

TEST(DecoderHeader, RejectsUnknownNames) {
  for (const char* name : {"", "sh-l", "sh-l65", "sh-l02", "sg-0", "sg-65", "ad-rgbx", "ambient"})
    EXPECT_FALSE(baker_decode::BasisDecoder(name, 1.0).valid()) << name;
}

TEST(DecoderHeader, VisibilityUsesChannelZerosFunctions) {
  std::mt19937 rng(kSeed);
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    const baker_decode::BasisDecoder decoder = importerDecoder(*basis);
    const SphericalFunctions& functions = basis->functions(0);
    std::vector<double> values(functions.count());
    for (int n = 0; n < 20; ++n) {
      const std::vector<float> v = randomCoefficients(rng, functions.count());
      const Eigen::Vector3d d = randomDirection(rng);
      functions.evaluate(d, values.data());
      double expected = 0.0;
      for (int i = 0; i < functions.count(); ++i) expected += values[i] * v[i];
      EXPECT_NEAR(decoder.visibility(v.data(), toDecoder(d)), expected, 1e-5) << name;
    }
  }
}

TEST(DecoderHeader, TrilinearWeightsInterpolateBetweenProbes) {
  const int dims[3] = {3, 2, 1};
  const baker_decode::Vec3 origin{1.0, -2.0, 0.5};
  const double spacing = 0.5;
  // One number per probe, linear in its position: interpolation must reproduce it.
  const auto linear = [](double x, double y, double z) { return float(2.0 * x - 3.0 * y + 0.25 * z + 1.0); };
  std::vector<float> values;
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i) values.push_back(linear(origin.x + spacing * i, origin.y + spacing * j, origin.z));

  const auto interpolate = [&](const baker_decode::Vec3& p) {
    const baker_decode::ProbeNeighbourhood n = baker_decode::probeNeighbourhood(p, origin, spacing, dims);
    const float* probes[8];
    double weightSum = 0.0;
    for (int c = 0; c < 8; ++c) {
      EXPECT_GE(n.probe[c], 0);
      EXPECT_LT(n.probe[c], std::int64_t(values.size()));
      probes[c] = &values[n.probe[c]];
      weightSum += n.weight[c];
    }
    EXPECT_NEAR(weightSum, 1.0, 1e-12);
    float out;
    baker_decode::blendProbes(probes, n.weight, 1, &out);
    return out;
  };
  EXPECT_NEAR(interpolate({1.7, -1.8, 0.5}), linear(1.7, -1.8, 0.5), 1e-5);
  EXPECT_NEAR(interpolate({2.0, -1.5, 0.5}), linear(2.0, -1.5, 0.5), 1e-5);  // the last probe
  EXPECT_EQ(interpolate({1.5, -2.0, 0.5}), values[1]);                         // exactly at probe (1, 0, 0)
  // Outside the grid: the nearest boundary point, like clamp-to-edge.
  EXPECT_NEAR(interpolate({0.0, -3.0, 9.0}), linear(1.0, -2.0, 0.5), 1e-5);
  EXPECT_NEAR(interpolate({5.0, -1.7, -4.0}), linear(2.0, -1.7, 0.5), 1e-5);
}

TEST(DecoderReconstructionData, ChannelsFollowTheLayout) {
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    const json data = reconstructionData(*basis, StoredSignal::Irradiance);
    EXPECT_EQ(data["variant"], name);
    EXPECT_EQ(data["color_space"], colorSpaceName(basis->colorSpace()));
    ASSERT_EQ(data["channels"].size(), 3u);
    for (int c = 0; c < 3; ++c) {
      const json& channel = data["channels"][c];
      EXPECT_EQ(channel["name"], channelName(basis->colorSpace(), c)) << name;
      EXPECT_EQ(channel["offset"], basis->coefficientOffset(c)) << name;
      EXPECT_EQ(channel["count"], basis->coefficientCount(c)) << name;
      EXPECT_EQ(data["function_sets"][channel["functions"].get<int>()]["count"], basis->coefficientCount(c)) << name;
    }
    EXPECT_EQ(data["function_sets"].size(), basis->channelsShareFunctions() ? 1u : 2u) << name;
    const std::string family = data["family"];
    EXPECT_TRUE(family == "sh" || family == "ambient-dice" || family == "ambient-cube" || family == "spherical-gaussians");
    EXPECT_EQ(family == "ambient-dice", data.contains("icosahedron")) << name;
    // Compact enough for a metadata string.
    EXPECT_LT(data.dump().size(), 6000u) << name;
  }
}

TEST(DecoderReconstructionData, ConvertsYCoCgToRgbLikeTheLibrary) {
  const json data = reconstructionData(*makeBasis("ad-ycocg"), StoredSignal::Irradiance);
  ASSERT_TRUE(data.contains("to_rgb"));
  const Eigen::Vector3f ycocg(0.7f, -0.2f, 0.15f);
  const Eigen::Vector3f rgb = toRgb(ColorSpace::YCoCg, ycocg);
  for (int row = 0; row < 3; ++row) {
    double value = 0.0;
    for (int column = 0; column < 3; ++column) value += data["to_rgb"][row][column].get<double>() * ycocg[column];
    EXPECT_NEAR(value, rgb[row], 1e-6);
  }
  const baker_decode::Rgb header = baker_decode::ycocgToRgb(ycocg.x(), ycocg.y(), ycocg.z());
  EXPECT_NEAR(header.r, rgb.x(), 1e-6);
  EXPECT_NEAR(header.g, rgb.y(), 1e-6);
  EXPECT_NEAR(header.b, rgb.z(), 1e-6);
  EXPECT_FALSE(reconstructionData(*makeBasis("ad-rgb"), StoredSignal::Irradiance).contains("to_rgb"));
}

TEST(DecoderReconstructionData, SphericalGaussianLobesPeakAtTheirAxes) {
  std::mt19937 rng(kSeed);
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    const json set = reconstructionData(*basis, StoredSignal::Irradiance)["function_sets"][0];
    if (set["type"] != "spherical-gaussians") continue;
    const SphericalFunctions& lobes = basis->functions(0);
    const double sharpness = set["sharpness"];
    ASSERT_EQ(int(set["axes"].size()), lobes.count());
    std::vector<double> values(lobes.count());
    for (int i = 0; i < lobes.count(); ++i) {
      const Eigen::Vector3d axis = fromJson(set["axes"][i]);
      const baker_decode::Vec3 header = baker_decode::sphericalFibonacciAxis(i, lobes.count());
      EXPECT_NEAR((axis - Eigen::Vector3d(header.x, header.y, header.z)).norm(), 0.0, 1e-12) << name << " lobe " << i;
      lobes.evaluate(axis, values.data());
      EXPECT_NEAR(values[i], 1.0, 1e-12) << name << " lobe " << i;
      // Away from the axis the lobe falls off as the JSON's formula says.
      for (int n = 0; n < 5; ++n) {
        const Eigen::Vector3d d = (axis + 0.5 * randomDirection(rng)).normalized();
        lobes.evaluate(d, values.data());
        EXPECT_LT(values[i], 1.0) << name;
        EXPECT_NEAR(values[i], std::exp(sharpness * (axis.dot(d) - 1.0)), 1e-12) << name;
      }
    }
  }
}

// Derivative on the sphere of function `f` of `functions` at unit `v` along unit tangent `t`.
// The step is small because at a vertex the two sides lie in different triangles, whose
// second derivatives differ: the central difference is then only first-order accurate.
double derivativeAlong(const SphericalFunctions& functions, int f, const Eigen::Vector3d& v, const Eigen::Vector3d& t) {
  const double step = 1e-7;
  std::vector<double> ahead(functions.count()), behind(functions.count());
  functions.evaluate((v + step * t).normalized(), ahead.data());
  functions.evaluate((v - step * t).normalized(), behind.data());
  return (ahead[f] - behind[f]) / (2.0 * std::atan(step));
}

void expectIcosahedronSetMatches(const std::string& name, const json& set, const json& icosahedron,
                                 const SphericalFunctions& functions) {
  const std::string type = set["type"];
  std::vector<double> values(functions.count());
  for (int i = 0; i < Icosahedron::kVertexCount; ++i) {
    const Eigen::Vector3d v = fromJson(icosahedron["vertices"][i]);
    functions.evaluate(v, values.data());
    for (int j = 0; j < Icosahedron::kVertexCount; ++j) {
      if (type == "icosahedron-linear") {
        EXPECT_NEAR(values[j], i == j ? 1.0 : 0.0, 1e-9) << name << " vertex " << i << " function " << j;
      } else if (type == "icosahedron-lobes") {
        // The lobe formula with the JSON's constants, at every vertex (c = 1, 1/√5, −1/√5, −1).
        const double c = std::max(0.0, fromJson(icosahedron["vertices"][j]).dot(v));
        const double lobe = set["cos2"].get<double>() * c * c + set["cos4"].get<double>() * c * c * c * c;
        EXPECT_NEAR(values[j], lobe, 1e-12) << name << " vertex " << i << " lobe " << j;
      } else {
        ASSERT_EQ(type, "icosahedron-bezier");
        EXPECT_NEAR(values[3 * j], i == j ? 1.0 : 0.0, 1e-9) << name << " vertex " << i << " value datum " << j;
        EXPECT_NEAR(values[3 * j + 1], 0.0, 1e-9) << name;
        EXPECT_NEAR(values[3 * j + 2], 0.0, 1e-9) << name;
      }
    }
    if (type != "icosahedron-bezier") continue;
    // The derivative data are the patch's gradient in the JSON's frame, scaled as it says.
    const Eigen::Vector3d t = fromJson(icosahedron["tangents"][i]), b = fromJson(icosahedron["bitangents"][i]);
    EXPECT_NEAR(t.dot(v), 0.0, 1e-12);
    EXPECT_NEAR(b.dot(v), 0.0, 1e-12);
    EXPECT_NEAR(t.cross(b).dot(v), 1.0, 1e-12);
    const double unit = 1.0 / set["stored_gradient_scale"].get<double>();
    EXPECT_NEAR(derivativeAlong(functions, 3 * i + 1, v, t), unit, 1e-6) << name << " vertex " << i;
    EXPECT_NEAR(derivativeAlong(functions, 3 * i + 1, v, b), 0.0, 1e-6) << name << " vertex " << i;
    EXPECT_NEAR(derivativeAlong(functions, 3 * i + 2, v, b), unit, 1e-6) << name << " vertex " << i;
    EXPECT_NEAR(derivativeAlong(functions, 3 * i + 2, v, t), 0.0, 1e-6) << name << " vertex " << i;
  }
}

TEST(DecoderReconstructionData, AmbientDiceFunctionsSitOnTheListedVertices) {
  int checked = 0;
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    const json data = reconstructionData(*basis, StoredSignal::Irradiance);
    if (data["family"] != "ambient-dice") continue;
    const json& icosahedron = data["icosahedron"];
    ASSERT_EQ(icosahedron["vertices"].size(), 12u);
    for (int i = 0; i < 12; ++i) {
      const baker_decode::Vec3 header = baker_decode::icosahedronVertex(i);
      EXPECT_NEAR((fromJson(icosahedron["vertices"][i]) - Eigen::Vector3d(header.x, header.y, header.z)).norm(), 0.0,
                  1e-12);
    }
    for (int c = 0; c < 3; ++c) {
      const json& set = data["function_sets"][data["channels"][c]["functions"].get<int>()];
      expectIcosahedronSetMatches(name, set, icosahedron, basis->functions(c));
    }
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

// An importer may find the triangle by trying the listed ones: the one where all spherical
// barycentrics are ≥ 0 must be the one the library uses.
TEST(DecoderReconstructionData, ListedTrianglesAreTheLibrarys) {
  const json icosahedron = reconstructionData(*makeBasis("ad-linear"), StoredSignal::Irradiance)["icosahedron"];
  ASSERT_EQ(icosahedron["triangles"].size(), 20u);
  std::mt19937 rng(kSeed);
  for (int n = 0; n < kDirections; ++n) {
    const Eigen::Vector3d d = randomDirection(rng);
    std::array<int, 3> found{-1, -1, -1};
    for (const json& triangle : icosahedron["triangles"]) {
      Eigen::Matrix3d corners;
      for (int k = 0; k < 3; ++k) corners.col(k) = fromJson(icosahedron["vertices"][triangle[k].get<int>()]);
      if ((corners.inverse() * d).minCoeff() >= 0.0) found = triangle.get<std::array<int, 3>>();
    }
    std::array<int, 3> expected = Icosahedron::instance().locate(d).vertices;
    std::sort(found.begin(), found.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(found, expected) << d.transpose();
  }
}

TEST(DecoderReconstructionData, AmbientCubeLobesSitOnTheListedAxes) {
  const auto basis = makeBasis("ambient-cube");
  const json set = reconstructionData(*basis, StoredSignal::Irradiance)["function_sets"][0];
  std::vector<double> values(6);
  for (int i = 0; i < 6; ++i) {
    basis->functions(0).evaluate(fromJson(set["axes"][i]), values.data());
    for (int j = 0; j < 6; ++j) EXPECT_EQ(values[j], i == j ? 1.0 : 0.0) << i << " " << j;
  }
}

TEST(DecoderReconstructionData, ShDataNamesTheOrder) {
  const json set = reconstructionData(*makeBasis("sh-l3"), StoredSignal::Irradiance)["function_sets"][0];
  EXPECT_EQ(set["type"], "sh");
  EXPECT_EQ(set["order"], 3);
  EXPECT_EQ(set["count"], 16);
}

}  // namespace
}  // namespace baker
