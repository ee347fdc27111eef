#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "basis/RadialLobes.h"

namespace baker {

// A finite set of real functions on the unit sphere, evaluated all at once at a direction.
// Bases are built from these; projection operators only ever see this interface.
class SphericalFunctions {
 public:
  virtual ~SphericalFunctions() = default;
  virtual int count() const = 0;
  // Writes count() values for the unit vector `direction`.
  virtual void evaluate(const Eigen::Vector3d& direction, double* values) const = 0;

  // Normals of the great circles (planes through the centre) across which some of the
  // functions are not smooth, beyond the 15 mirror planes of the icosahedron (which contain
  // its edges and the coordinate planes): exact quadratures split the sphere along them.
  // E.g. clamped lobes max(0, v·d)^p kink on the plane v·d = 0.
  virtual std::vector<Eigen::Vector3d> kinkPlanes() const { return {}; }

  // The degree d when every function is a polynomial of degree ≤ d in the direction's
  // coordinates, −1 otherwise: products of polynomials have an exact quadrature with a few
  // hundred nodes, where piecewise-smooth functions need the icosahedral tiling's many.
  virtual int polynomialDegree() const { return -1; }

  // The profile and axes when every function is one profile of the cosine to its own axis:
  // their diffuse response is then a one-dimensional series a decoder evaluates.
  virtual std::optional<RadialLobes> radialLobes() const { return std::nullopt; }
  // L when the set is the real SH of bands 0 … L in their standard order, −1 otherwise: their
  // diffuse response is then the clamped cosine's band factors alone.
  virtual int shBands() const { return -1; }

  // The set as data an importer evaluates without this code: "type", the constants of its
  // formula in docs/DECODERS.md, and "count" (added by the caller). A volume's file carries it;
  // sets that only serve computations (quadrature tests, SH band subsets) need none.
  virtual nlohmann::json describe() const {
    throw std::logic_error("a volume cannot store these functions: they have no description for its file");
  }
  // The parameters that tell this set from others of its type, for messages ("sharpness 8");
  // empty when its type alone does.
  virtual std::string parameterText() const { return {}; }
};

}  // namespace baker
