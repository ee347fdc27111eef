#include "basis/SpecularBlend.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "basis/DiffuseResponse.h"
#include "basis/DirectionSet.h"
#include "basis/GgxLobe.h"

namespace baker {
namespace {

// Nodes of each lobe's quadrature. With twice the frames and 1.5 times the nodes per axis the
// weights move by under 0.006 for ad-srbf and 0.06 for ad-ycocg (at grazing views): small
// beside what a blend of two terms cannot follow, and the table costs a bake 0.3 s, not 1 s.
constexpr int kUNodes = 16, kPhiNodes = 32;

struct FunctionSet {
  const SphericalFunctions* functions;
  std::shared_ptr<const DiffuseResponse> response;
};

std::vector<FunctionSet> distinctSets(const Basis& basis) {
  std::vector<FunctionSet> sets;
  for (int c = 0; c < 3; ++c)
    if (c == 0 || &basis.functions(c) != &basis.functions(c - 1))
      sets.push_back({&basis.functions(c), diffuseResponseOf(basis, c)});
  return sets;
}

// A view at n·v = cosView from normal n, its azimuth turned by a golden angle per frame so that
// the frames do not line up with any symmetry of the basis.
Eigen::Vector3d viewFrom(const Eigen::Vector3d& n, double cosView, int frame) {
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  const double phi = 2.399963229728653 * frame;
  const Eigen::Vector3d tangent = std::cos(phi) * u + std::sin(phi) * w;
  return cosView * n + std::sqrt(std::max(0.0, 1.0 - cosView * cosView)) * tangent;
}

// The least-squares weight over every function and frame: with a = E/π − L(r) and b = S − L(r),
// w = Σab / Σa², kept in [0, 1] so that S stays a blend.
double fittedWeight(const std::vector<FunctionSet>& sets, const DirectionSet& normals, double roughness,
                    double cosView) {
  double aa = 0.0, ab = 0.0;
  std::vector<double> values, mirror, response, specular;
  for (std::size_t f = 0; f < normals.size(); ++f) {
    const Eigen::Vector3d& n = normals.directions[f];
    const GgxLobe lobe(n, viewFrom(n, cosView, int(f)), roughness);
    const DirectionSet q = lobe.quadrature(kUNodes, kPhiNodes);
    double albedo = 0.0;
    for (double w : q.weights) albedo += w;
    if (!(albedo > 1e-12)) continue;
    for (const FunctionSet& set : sets) {
      const int count = set.functions->count();
      values.assign(std::size_t(count), 0.0);
      mirror.assign(std::size_t(count), 0.0);
      response.assign(std::size_t(count), 0.0);
      specular.assign(std::size_t(count), 0.0);
      for (std::size_t s = 0; s < q.size(); ++s) {
        set.functions->evaluate(q.directions[s], values.data());
        for (int i = 0; i < count; ++i) specular[std::size_t(i)] += q.weights[s] * values[std::size_t(i)];
      }
      set.functions->evaluate(lobe.reflection(), mirror.data());
      set.response->evaluate(n, response.data());
      for (int i = 0; i < count; ++i) {
        const double a = response[std::size_t(i)] / M_PI - mirror[std::size_t(i)];
        const double b = specular[std::size_t(i)] / albedo - mirror[std::size_t(i)];
        aa += a * a;
        ab += a * b;
      }
    }
  }
  return aa > 1e-30 ? std::clamp(ab / aa, 0.0, 1.0) : 0.0;
}

}  // namespace

SpecularBlend::SpecularBlend(const Basis& basis) {
  const std::vector<FunctionSet> sets = distinctSets(basis);
  const DirectionSet normals = sphericalFibonacci(kFrames);
  // Each cell is its own computation, so the table is the same at any thread count. Isolated:
  // while this thread holds specularBlendOf's lock, waiting for the loop must not let it pick up
  // an outer task that calls specularBlendOf again.
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(0, kSteps * kSteps, [&](int cell) {
      const int j = cell / kSteps, k = cell % kSteps;
      // Roughness 0 is the mirror, S = L(r) exactly: its fit would give 0 up to rounding.
      weight_[std::size_t(j)][std::size_t(k)] = j == 0 ? 0.0 : fittedWeight(sets, normals, node(j), node(k));
      albedo_[std::size_t(j)][std::size_t(k)] =
          GgxLobe(Eigen::Vector3d::UnitZ(), viewFrom(Eigen::Vector3d::UnitZ(), node(k), 0), node(j)).albedo();
    });
  });
}

double SpecularBlend::lookup(const Table& table, double roughness, double cosView) {
  if (std::isnan(roughness) || std::isnan(cosView)) throw std::invalid_argument("specular lookup at NaN");
  const double x = std::clamp(roughness, 0.0, 1.0) * (kSteps - 1), y = std::clamp(cosView, 0.0, 1.0) * (kSteps - 1);
  const int j = std::min(int(x), kSteps - 2), k = std::min(int(y), kSteps - 2);
  const double fx = x - j, fy = y - k;
  const auto at = [&](int a, int b) { return table[std::size_t(a)][std::size_t(b)]; };
  return (1.0 - fx) * ((1.0 - fy) * at(j, k) + fy * at(j, k + 1)) + fx * ((1.0 - fy) * at(j + 1, k) + fy * at(j + 1, k + 1));
}

nlohmann::json SpecularBlend::describe() const {
  nlohmann::json nodes = nlohmann::json::array(), weights = nlohmann::json::array(), albedos = nlohmann::json::array();
  for (int j = 0; j < kSteps; ++j) {
    nodes.push_back(node(j));
    weights.push_back(weight_[std::size_t(j)]);
    albedos.push_back(albedo_[std::size_t(j)]);
  }
  return {{"brdf", "GGX, F0 = 1, height-correlated Smith G2, alpha = roughness^2 (glTF)"},
          {"value",
           "specular S = (1 - w) L(r) + w E(n)/pi, r = 2 (n.v) n - v: the GGX-weighted mean of the radiance; "
           "reflected radiance = albedo * F * S"},
          {"lookup", "w and albedo bilinear in (roughness, n.v) between the nodes, both clamped to [0, 1]"},
          {"roughness", nodes},
          {"cos_view", nodes},
          {"diffuse_weight", weights},
          {"albedo", albedos}};
}

std::shared_ptr<const SpecularBlend> specularBlendOf(const Basis& basis) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const SpecularBlend>> built;
  const std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<const SpecularBlend>& blend = built[basis.identity()];
  if (!blend) blend = std::make_shared<const SpecularBlend>(basis);
  return blend;
}

}  // namespace baker
