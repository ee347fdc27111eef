#pragma once
#include "basis/Basis.h"
#include "basis/Icosahedron.h"

namespace baker {

// One value per icosahedron vertex, interpolated linearly across each triangle: 12 functions,
// function i the "hat" of vertex i (its barycentric in the 5 triangles around it, 0 elsewhere).
// With flat barycentrics the hats sum to 1; with spherical ones they do not, but they are
// still continuous, since on an edge the third barycentric is 0 in both triangles.
class AmbientDiceLinearFunctions : public SphericalFunctions {
 public:
  explicit AmbientDiceLinearFunctions(Barycentrics kind) : kind_(kind) {}
  Barycentrics barycentrics() const { return kind_; }
  int count() const override { return Icosahedron::kVertexCount; }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;

 private:
  Barycentrics kind_;
};

// Ambient Dice with linear interpolation of RGB vertex values in flat barycentrics, CLI name
// "ad-linear": per channel coefficient i is the value at vertex i; 3·12 stored, 3·3 read.
class AmbientDiceLinear : public Basis {
 public:
  AmbientDiceLinear() : functions_(Barycentrics::Flat) {}
  std::string name() const override { return "ad-linear"; }
  std::string family() const override { return "ambient-dice"; }
  const SphericalFunctions& functions(int) const override { return functions_; }
  int coefficientsPerLookup() const override { return 9; }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  AmbientDiceLinearFunctions functions_;
};

}  // namespace baker
