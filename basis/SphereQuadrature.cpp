#include "basis/SphereQuadrature.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <stdexcept>

#include "basis/Icosahedron.h"
#include "basis/Quadrature.h"

namespace baker {
namespace {

using Polygon = std::vector<Eigen::Vector3d>;

// Splits a convex planar polygon by the plane n·p = 0 into its parts on either side.
void clip(const Polygon& poly, const Eigen::Vector3d& n, std::vector<Polygon>* out) {
  Polygon positive, negative;
  const std::size_t count = poly.size();
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % count];
    const double da = n.dot(a), db = n.dot(b);
    if (da >= 0.0) positive.push_back(a);
    if (da <= 0.0) negative.push_back(a);
    if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) {
      const Eigen::Vector3d cut = a + (b - a) * (da / (da - db));
      positive.push_back(cut);
      negative.push_back(cut);
    }
  }
  for (Polygon* part : {&positive, &negative})
    if (part->size() >= 3) out->push_back(std::move(*part));
}

double polygonArea(const Polygon& poly) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) sum += (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]);
  return 0.5 * sum.norm();
}

// A piece of the tiling on the face of the icosahedron it lies in, and that face plane's distance
// from the centre.
struct FlatPiece {
  Polygon corners;
  double height;
};

// The tiling's pieces, cut by the planes.
std::vector<FlatPiece> tilingPieces(const std::vector<Eigen::Vector3d>& kinkPlanes) {
  const Icosahedron& ico = Icosahedron::instance();
  std::vector<FlatPiece> pieces;
  for (int t = 0; t < Icosahedron::kTriangleCount; ++t) {
    const std::array<Eigen::Vector3d, 3> face = {ico.vertex(ico.triangle(t)[0]), ico.vertex(ico.triangle(t)[1]),
                                                 ico.vertex(ico.triangle(t)[2])};
    const Eigen::Vector3d centre = (face[0] + face[1] + face[2]) / 3.0;
    const Eigen::Vector3d normal = (face[1] - face[0]).cross(face[2] - face[0]).normalized();
    const double height = std::abs(normal.dot(face[0]));
    // Six triangles per face, split along its medians (which lie on mirror planes), each with
    // an icosahedron vertex first.
    std::vector<Polygon> facePieces;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& apex = face[k];
      const Eigen::Vector3d next = 0.5 * (face[k] + face[(k + 1) % 3]);
      const Eigen::Vector3d previous = 0.5 * (face[k] + face[(k + 2) % 3]);
      facePieces.push_back({apex, next, centre});
      facePieces.push_back({apex, centre, previous});
    }
    for (const Eigen::Vector3d& plane : kinkPlanes) {
      std::vector<Polygon> cut;
      for (const Polygon& piece : facePieces) clip(piece, plane, &cut);
      facePieces.swap(cut);
    }
    for (Polygon& piece : facePieces)  // leaving out the slivers left by planes through corners
      if (polygonArea(piece) >= 1e-14) pieces.push_back({std::move(piece), height});
  }
  return pieces;
}

// Gauss–Legendre nodes and weights of `order` mapped to [0, 1].
struct UnitRule {
  std::vector<double> x, w;
};
UnitRule unitGaussLegendre(int order) {
  if (order < 1) throw std::invalid_argument("quadrature order must be positive");
  UnitRule rule;
  gaussLegendre(order, &rule.x, &rule.w);
  for (std::size_t i = 0; i < rule.x.size(); ++i) {
    rule.x[i] = 0.5 * (rule.x[i] + 1.0);
    rule.w[i] *= 0.5;
  }
  return rule;
}

std::size_t nodeCount(const FlatPiece& piece, const UnitRule& rule) {
  return (piece.corners.size() - 2) * rule.x.size() * rule.x.size();
}

// The nodes of one piece, nodeCount of them, into `directions` and `weights`.
void pieceNodes(const FlatPiece& flat, const UnitRule& rule, Eigen::Vector3d* directions, double* weights) {
  const Polygon& piece = flat.corners;
  const std::size_t order = rule.x.size();
  std::size_t node = 0;
  for (std::size_t corner = 1; corner + 1 < piece.size(); ++corner) {
    // Duffy map of the unit square onto (p0, p1, p2): p = p0 + u(p1 − p0) + uv(p2 − p1),
    // dA = u·|(p1 − p0) × (p2 − p1)| du dv, collapsing the edge u = 0 onto p0.
    const Eigen::Vector3d& p0 = piece[0];
    const Eigen::Vector3d e1 = piece[corner] - p0, e2 = piece[corner + 1] - piece[corner];
    const double area2 = e1.cross(e2).norm();
    for (std::size_t i = 0; i < order; ++i)
      for (std::size_t j = 0; j < order; ++j, ++node) {
        const double u = rule.x[i], v = rule.x[j];
        const Eigen::Vector3d point = p0 + u * e1 + u * v * e2;
        const double r = point.norm();
        // Gnomonic Jacobian: a flat area dA at p subtends dω = dA·(n̂·p)/|p|³.
        weights[node] = rule.w[i] * rule.w[j] * u * area2 * flat.height / (r * r * r);
        directions[node] = point / r;
      }
  }
}

}  // namespace

DirectionSet piecewiseSphereQuadrature(int order, const std::vector<Eigen::Vector3d>& kinkPlanes) {
  const UnitRule rule = unitGaussLegendre(order);
  // Every piece is cut first and its nodes given their place in the rule, so that the rule is
  // stored once and its pieces filled in parallel: grown node by node, its copies took most of
  // the time of building an Ambient Dice basis's operators. The nodes come in the order of the
  // pieces at any thread count.
  const std::vector<FlatPiece> pieces = tilingPieces(kinkPlanes);
  std::vector<std::size_t> firstNode(pieces.size() + 1, 0);
  for (std::size_t p = 0; p < pieces.size(); ++p) firstNode[p + 1] = firstNode[p] + nodeCount(pieces[p], rule);
  DirectionSet set;
  set.directions.resize(firstNode.back());
  set.weights.resize(firstNode.back());
  tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t p) {
    pieceNodes(pieces[p], rule, set.directions.data() + firstNode[p], set.weights.data() + firstNode[p]);
  });
  return set;
}

Eigen::VectorXd sumOverSphereQuadrature(int order, const std::vector<Eigen::Vector3d>& kinkPlanes, int size,
                                        const std::function<void(const DirectionSet&, Eigen::VectorXd*)>& add) {
  const UnitRule rule = unitGaussLegendre(order);
  const std::vector<FlatPiece> pieces = tilingPieces(kinkPlanes);
  std::vector<Eigen::VectorXd> partial(pieces.size(), Eigen::VectorXd::Zero(size));
  tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t p) {
    DirectionSet nodes;  // its own for each piece: `add` may itself wait on other work in parallel
    nodes.directions.resize(nodeCount(pieces[p], rule));
    nodes.weights.resize(nodes.directions.size());
    pieceNodes(pieces[p], rule, nodes.directions.data(), nodes.weights.data());
    add(nodes, &partial[p]);
  });
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(size);
  for (const Eigen::VectorXd& piece : partial) sum += piece;
  return sum;
}

}  // namespace baker
