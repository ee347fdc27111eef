#pragma once
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "basis/DirectionSet.h"

namespace baker {

// A quadrature on the sphere for functions that are smooth on each piece of the icosahedral
// tiling (the 120 triangles cut out by the icosahedron's 15 mirror planes, which contain its
// edges and the coordinate planes), further cut by the planes through the centre with normals
// `kinkPlanes`. Every piece is mapped gnomonically onto a flat triangle and integrated with an
// `order`×`order` Gauss–Legendre rule in collapsed (Duffy) coordinates whose apex sits on an
// icosahedron vertex, where the hybrid Bézier blend is only direction-continuous. On smooth
// pieces the error falls exponentially with `order`; see SphereQuadratureTest.
DirectionSet piecewiseSphereQuadrature(int order, const std::vector<Eigen::Vector3d>& kinkPlanes = {});

// Σ over the same rule without holding it, for a sum that needs each node once: `add` sums over
// one piece's nodes (valid during the call) into a zeroed vector of `size`, called for several
// pieces at once from different threads, and the pieces' sums are added in piece order, so that
// any thread count gives the same bits.
Eigen::VectorXd sumOverSphereQuadrature(int order, const std::vector<Eigen::Vector3d>& kinkPlanes, int size,
                                        const std::function<void(const DirectionSet&, Eigen::VectorXd*)>& add);

}  // namespace baker
