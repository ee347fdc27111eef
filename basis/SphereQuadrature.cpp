#include "basis/SphereQuadrature.h"

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

}  // namespace

DirectionSet piecewiseSphereQuadrature(int order, const std::vector<Eigen::Vector3d>& kinkPlanes) {
  if (order < 1) throw std::invalid_argument("quadrature order must be positive");
  std::vector<double> x, w;
  gaussLegendre(order, &x, &w);
  for (std::size_t i = 0; i < x.size(); ++i) {  // map to [0, 1]
    x[i] = 0.5 * (x[i] + 1.0);
    w[i] *= 0.5;
  }

  DirectionSet set;
  const Icosahedron& ico = Icosahedron::instance();
  for (int t = 0; t < Icosahedron::kTriangleCount; ++t) {
    const std::array<Eigen::Vector3d, 3> face = {ico.vertex(ico.triangle(t)[0]), ico.vertex(ico.triangle(t)[1]),
                                                 ico.vertex(ico.triangle(t)[2])};
    const Eigen::Vector3d centre = (face[0] + face[1] + face[2]) / 3.0;
    const Eigen::Vector3d normal = (face[1] - face[0]).cross(face[2] - face[0]).normalized();
    const double height = std::abs(normal.dot(face[0]));  // distance of the face plane from the centre
    // Six triangles per face, split along its medians (which lie on mirror planes), each with
    // an icosahedron vertex first.
    std::vector<Polygon> pieces;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& apex = face[k];
      const Eigen::Vector3d next = 0.5 * (face[k] + face[(k + 1) % 3]);
      const Eigen::Vector3d previous = 0.5 * (face[k] + face[(k + 2) % 3]);
      pieces.push_back({apex, next, centre});
      pieces.push_back({apex, centre, previous});
    }
    for (const Eigen::Vector3d& plane : kinkPlanes) {
      std::vector<Polygon> cut;
      for (const Polygon& piece : pieces) clip(piece, plane, &cut);
      pieces.swap(cut);
    }
    for (const Polygon& piece : pieces) {
      if (polygonArea(piece) < 1e-14) continue;  // a sliver left by a plane through a corner
      for (std::size_t corner = 1; corner + 1 < piece.size(); ++corner) {
        // Duffy map of the unit square onto (p0, p1, p2): p = p0 + u(p1 − p0) + uv(p2 − p1),
        // dA = u·|(p1 − p0) × (p2 − p1)| du dv, collapsing the edge u = 0 onto p0.
        const Eigen::Vector3d& p0 = piece[0];
        const Eigen::Vector3d e1 = piece[corner] - p0, e2 = piece[corner + 1] - piece[corner];
        const double area2 = e1.cross(e2).norm();
        for (int i = 0; i < order; ++i)
          for (int j = 0; j < order; ++j) {
            const double u = x[i], v = x[j];
            const Eigen::Vector3d p = p0 + u * e1 + u * v * e2;
            const double r = p.norm();
            // Gnomonic Jacobian: a flat area dA at p subtends dω = dA·(n̂·p)/|p|³.
            set.weights.push_back(w[i] * w[j] * u * area2 * height / (r * r * r));
            set.directions.push_back(p / r);
          }
      }
    }
  }
  return set;
}

}  // namespace baker
