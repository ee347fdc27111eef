#pragma once
#include <vector>

#include "basis/DirectionSet.h"

namespace baker {

// Nodes and weights of n-point Gauss–Legendre quadrature on [-1, 1]: exact for polynomials
// of degree up to 2n − 1.
void gaussLegendre(int n, std::vector<double>* nodes, std::vector<double>* weights);

// Gauss–Legendre in z = cos θ times `phiCount` equally spaced φ: exact on the sphere for
// polynomials in (x, y, z) of degree below min(2·zCount, phiCount).
DirectionSet gaussProductSphere(int zCount, int phiCount);

}  // namespace baker
