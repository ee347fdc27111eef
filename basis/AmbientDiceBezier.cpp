#include "basis/AmbientDiceBezier.h"

#include <algorithm>
#include <cmath>

#include "basis/BasisRegistry.h"

namespace baker {
namespace {

// The c111 blend weights. Barycentrics a rounding error outside the triangle are clamped so
// the weights stay convex; where two are 0 (a vertex) the blend is that vertex's own.
Eigen::Vector3d centreBlend(const Eigen::Vector3d& b) {
  const Eigen::Vector3d p = b.cwiseMax(0.0);
  const Eigen::Vector3d q(p[1] * p[2], p[0] * p[2], p[0] * p[1]);
  const double sum = q.sum();
  if (sum > 0.0) return q / sum;
  Eigen::Vector3d own = Eigen::Vector3d::Zero();
  own[std::max_element(p.data(), p.data() + 3) - p.data()] = 1.0;
  return own;
}

}  // namespace

double AmbientDiceBezierFunctions::alpha() { return 0.5 * std::sqrt((5.0 + std::sqrt(5.0)) / 2.0); }

AmbientDiceBezierFunctions::AmbientDiceBezierFunctions(Barycentrics kind) : kind_(kind) {
  const double root5 = std::sqrt(5.0);
  if (kind == Barycentrics::Spherical) {
    vertexFactor_ = 1.0 / root5;
    a0_ = (root5 - 5.0) / 40.0;
    a1_ = (11.0 * root5 - 15.0) / 40.0;
    a2_ = root5 / 10.0;
  } else {
    vertexFactor_ = 1.0;
    a0_ = -0.25;
    a1_ = 0.25;
    a2_ = 0.5;
  }
  // The paper's edge points: if the edge tangent at v0 has barycentrics (β, α, 0), the cubic
  // changes along it at 3(β c300 + α c210), which gives c210 from f(v0) and the derivative
  // (vf = −β/α; flat barycentrics move at (−α, α, 0), so there vf = 1). The paper's α, kept
  // for compatibility, is off by cos(θ/2): see the header.
  const Icosahedron& ico = Icosahedron::instance();
  for (int t = 0; t < Icosahedron::kTriangleCount; ++t)
    for (int k = 0; k < 3; ++k)
      for (int m = 0; m < 3; ++m) {
        if (m == k) continue;
        const int i = ico.triangle(t)[k], j = ico.triangle(t)[m];
        const Eigen::Vector3d& v = ico.vertex(i);
        const Eigen::Vector3d e = (ico.vertex(j) - v.dot(ico.vertex(j)) * v).normalized();
        edgeFactors_[t][3 * k + m] = Eigen::Vector2d(e.dot(ico.tangent(i)), e.dot(ico.bitangent(i))) / (3.0 * alpha());
      }
}

void AmbientDiceBezierFunctions::localWeights(const TrianglePoint& p, double* weights) const {
  const Eigen::Vector3d& b = p.barycentrics(kind_);
  const std::array<Eigen::Vector2d, 9>& edge = edgeFactors_[p.triangle];
  std::fill(weights, weights + 9, 0.0);
  const auto vertexPoint = [&](int k, double w) { weights[3 * k] += w; };
  // The control point on the edge from corner k towards m, next to k.
  const auto edgePoint = [&](int k, int m, double w) {
    const Eigen::Vector2d& g = edge[3 * k + m];
    weights[3 * k] += vertexFactor_ * w;
    weights[3 * k + 1] += g.x() * w;
    weights[3 * k + 2] += g.y() * w;
  };
  for (int k = 0; k < 3; ++k) {
    vertexPoint(k, b[k] * b[k] * b[k]);
    for (int m = 0; m < 3; ++m)
      if (m != k) edgePoint(k, m, 3.0 * b[k] * b[k] * b[m]);
  }
  const Eigen::Vector3d blend = centreBlend(b);
  const double centre = 6.0 * b[0] * b[1] * b[2];
  for (int j = 0; j < 3; ++j) {
    const double w = centre * blend[j];
    const int k = (j + 1) % 3, m = (j + 2) % 3;  // c111^(j) is built from the edge opposite corner j
    vertexPoint(k, a0_ * w);
    vertexPoint(m, a0_ * w);
    edgePoint(k, m, a1_ * w);
    edgePoint(m, k, a1_ * w);
    edgePoint(k, j, a2_ * w);
    edgePoint(m, j, a2_ * w);
  }
}

void AmbientDiceBezierFunctions::evaluate(const Eigen::Vector3d& d, double* values) const {
  std::fill(values, values + count(), 0.0);
  const TrianglePoint p = Icosahedron::instance().locate(d);
  double local[9];
  localWeights(p, local);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) values[3 * p.vertices[k] + j] = local[3 * k + j];
}

std::string AmbientDiceBezier::name() const {
  return functions_.barycentrics() == Barycentrics::Spherical ? "ad-rgb" : "ad-rgb-flat";
}

Eigen::Vector3f AmbientDiceBezier::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  const TrianglePoint p = Icosahedron::instance().locate(d);
  double local[9];
  functions_.localWeights(p, local);
  Eigen::Vector3f rgb;
  for (int c = 0; c < 3; ++c) {
    const float* channel = coefficients + c * functions_.count();
    double sum = 0.0;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) sum += local[3 * k + j] * channel[3 * p.vertices[k] + j];
    rgb[c] = float(sum);
  }
  return rgb;
}

namespace {

const BasisRegistration kBezier({40, {"ad-rgb", "ad-rgb-flat"}, {},
                                 [](const std::string& name, const BasisParameters&) -> std::unique_ptr<Basis> {
                                   if (name == "ad-rgb") return std::make_unique<AmbientDiceBezier>(Barycentrics::Spherical);
                                   if (name == "ad-rgb-flat") return std::make_unique<AmbientDiceBezier>(Barycentrics::Flat);
                                   return nullptr;
                                 }});

}  // namespace

nlohmann::json AmbientDiceBezierFunctions::describe() const {
  // The angle θ between neighbouring icosahedron vertices enters the derivatives' units.
  const Icosahedron& ico = Icosahedron::instance();
  const std::array<int, 3>& corners = ico.triangle(0);
  const double halfEdgeCosine = std::sqrt(0.5 * (1.0 + ico.vertex(corners[0]).dot(ico.vertex(corners[1]))));
  return {{"type", "icosahedron-bezier"},
          {"barycentrics", barycentricsName(barycentrics())},
          {"per_vertex", nlohmann::json::array({"value", "d_tangent", "d_bitangent"})},
          {"patch", "hybrid cubic Bezier triangle of Ambient Dice (Iwanicki and Sloan 2017, 2.3.1): docs/DECODERS.md"},
          {"index", "3 vertex + datum"},
          {"vertex_factor", vertexFactor()},
          {"interior", interiorWeights()},
          {"alpha", alpha()},
          {"stored_gradient_scale", halfEdgeCosine},
          {"derivatives",
           "(d_tangent, d_bitangent) = stored_gradient_scale times the patch's gradient on the sphere at the vertex, "
           "in the vertex's (tangent, bitangent) frame"}};
}

}  // namespace baker
