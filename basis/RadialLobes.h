#pragma once
#include <Eigen/Core>
#include <functional>
#include <vector>

namespace baker {

// A function set whose function i is one profile of the cosine to its own axis, g(axis_i·ω).
// Such a lobe's diffuse response is the same kind of function of n·axis_i, so it is known
// everywhere from a one-dimensional series (basis/LegendreResponse.h) instead of the set's SH
// moments; decoders evaluate it from that series alone.
struct RadialLobes {
  std::function<double(double)> profile;  // g(t) for t ∈ [−1, 1]
  std::vector<Eigen::Vector3d> axes;      // unit, one per function, in the set's order
};

}  // namespace baker
