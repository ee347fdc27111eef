#pragma once
#include <Eigen/Core>
#include <vector>

namespace baker {

// A probe's distances to the first surface around it, for leak-aware sampling (Majercik et al.,
// "Dynamic Diffuse Global Illumination with Ray-Traced Irradiance Fields", JCGT 2019): per texel
// of a small octahedral map, the mean distance and the mean squared distance of the probe's rays
// near the texel's direction. A reader compares a point's distance with them (Chebyshev's
// inequality) and turns away a probe that a wall hides from the point.
//
// The map: direction d (+Y up) goes to p = (d.x, d.z) / (|d.x| + |d.y| + |d.z|), folded for
// d.y < 0 to ((1 − |p.y|)·sign p.x, (1 − |p.x|)·sign p.y) (sign 0 = +1); (u, v) = (p + 1)/2.
// Texel (i, j) of N × N covers u in [i, i + 1)/N, v in [j, j + 1)/N; it is stored as values
// 2t (mean distance) and 2t + 1 (mean squared distance), t = i + N·j, both in units of the cap
// (mean/cap and mean square/cap², in [0, 1]: half floats hold them at any scene scale).
//
// Distances are capped at `cap` (2.5 spacings: beyond any point of the probe's eight cells, √3
// spacings, moved by a relocation and the reader's normal bias); a ray that escapes counts as the
// cap, so a texel of 1 and 1 is open: no surface within reach. Each ray ω adds to every texel c with the weight max(0, c·ω)^k,
// k = ln 2 / −ln cos(√π / N) rounded to an integer: half weight half a texel's width away (k = 28
// for N = 8). An integer power is a few multiplications; exp and log of every ray at every texel
// it reaches took a quarter of a bake with a quality preset.
struct DistanceMapLayout {
  static constexpr int kDefaultSize = 8;
  static constexpr double kCapSpacings = 2.5;
  int size = kDefaultSize;  // texels per side
  double cap = 0.0;         // world units
  // Whether a third map follows the two moments: per texel t, value 2·texels + t, the share of the
  // lobe's rays that escaped to the sky (weighted as the moments are): the sky visibility
  // relighting reads at the map's resolution (volume/SkyTransfer.h). Volumes before it hold none.
  bool skyVisibility = false;

  // The layout a bake writes now: the moments and the sky's share.
  static DistanceMapLayout baked(int size, double cap) { return {size, cap, true}; }

  int texels() const { return size * size; }
  int valuesPerProbe() const { return (skyVisibility ? 3 : 2) * texels(); }
  double sharpness() const;
  Eigen::Vector3d texelDirection(int texel) const;
};

// Octahedral coordinates (u, v) in [0, 1]² of unit direction d, and back.
Eigen::Vector2d octahedralEncode(const Eigen::Vector3d& d);
Eigen::Vector3d octahedralDecode(const Eigen::Vector2d& uv);

// The map's texels as lobes: ray ω adds to texel t with the weight max(0, c)^k, c = ω·(t's
// direction), left out where it is below 1e-4. The ray-by-ray sums and the lattice weights both
// take their cosines and weights from here, so that the two agree bit for bit.
class TexelLobes {
 public:
  explicit TexelLobes(const DistanceMapLayout& layout);
  int texels() const { return int(x_.size()); }
  double cosine(int texel, const Eigen::Vector3d& d) const {
    return x_[std::size_t(texel)] * d.x() + y_[std::size_t(texel)] * d.y() + z_[std::size_t(texel)] * d.z();
  }
  bool reaches(double cosine) const { return cosine > cutoff_; }
  // c^k by squaring; only where reaches(c).
  double weight(double cosine) const;
  int power() const { return power_; }
  double cutoff() const { return cutoff_; }

 private:
  int power_;
  double cutoff_;  // the cosine at which the weight falls to 1e-4
  std::vector<double> x_, y_, z_;
};

// Each texel's weights for one fixed set of directions, worked out once: a bake's fixed lattices
// are a few rotations of one set, and working out 64 powers per ray for every probe took a
// quarter of a bake. Per texel, the rays its lobe reaches, in ray order, and its nearest ray.
class DistanceLatticeWeights {
 public:
  DistanceLatticeWeights(const DistanceMapLayout& layout, const Eigen::Vector3f* directions, int count);

 private:
  friend class DistanceMomentsAccumulator;
  int rays_;
  std::vector<int> texelStart_;  // texel t's rays are entries texelStart_[t] to texelStart_[t + 1]
  std::vector<int> ray_;
  std::vector<double> weight_;
  std::vector<int> nearestRay_;
  std::vector<double> nearestCosine_;
};

// Accumulates one probe's rays (in any number of batches, always in the same order: the sums are
// the same at any thread count).
class DistanceMomentsAccumulator {
 public:
  explicit DistanceMomentsAccumulator(const DistanceMapLayout& layout);
  void reset();
  // `distances[r]`: to the first hit along unit `directions[r]`, or +∞ when the ray escaped. The
  // rays are a lattice's: each weighs the same.
  void add(const Eigen::Vector3f* directions, const float* distances, int count);
  // The same sums, bit for bit, for the set of directions `weights` was made for (std::logic_error
  // for weights of a map of another size).
  void add(const DistanceLatticeWeights& weights, const float* distances);
  // Whether `other` holds the very same sums, bit for bit, and for each texel no lobe has reached
  // the same nearest ray (what write() reads).
  bool holdsTheSameSumsAs(const DistanceMomentsAccumulator& other) const;
  // 2·texels values in units of the cap, then (with skyVisibility) texels escaped shares; a texel
  // whose lobe no ray reached holds the nearest ray's.
  void write(float* moments) const;

 private:
  DistanceMapLayout layout_;
  TexelLobes lobes_;
  std::vector<double> weight_, sum_, sumSquares_, escaped_;
  // Per texel, the ray closest to it: what a texel no lobe reaches holds (with few rays, large N).
  // Ray by ray, it is followed only while some texel has not been reached.
  std::vector<double> nearestCosine_, nearestDistance_, nearestEscaped_;
  int unreached_ = 0;  // texels whose weight is still 0
  std::vector<double> rayDistance_, rayEscaped_;  // per ray of the lattice being added
  std::vector<double> cosines_;                   // per texel, of the ray being added
  std::vector<int> reached_;                      // the texels the ray's lobes reach
};

// The four texels a read at direction d blends, bilinearly between texel centres (clamped at the
// map's edges), and their weights.
struct TexelBlend {
  int texel[4] = {0, 0, 0, 0};
  double weight[4] = {0.0, 0.0, 0.0, 0.0};
};
TexelBlend blendTexels(const DistanceMapLayout& layout, const Eigen::Vector3d& d);

// The two moments at direction d in world units, bilinear between texel centres (clamped at the
// map's edges); `open` when each texel read holds the cap: no surface within reach that way.
struct DistanceMomentsRead {
  double mean = 0.0, meanSquare = 0.0;
  bool open = false;
};
DistanceMomentsRead readDistanceMoments(const DistanceMapLayout& layout, const float* moments, const Eigen::Vector3d& d);

// The weight that turns away a probe hidden from a shading point, in (0, 1]:
//  - exactly 1 where the probe's map reads open towards the point (mean at the cap: no surface
//    within reach), so that in open space leak-aware sampling is trilinear sampling;
//  - otherwise the back-face weight (((n·ω + 1)/2)² + 0.2)/1.2, ω from the biased point to the
//    probe, times Chebyshev's bound σ²/(σ² + (r − μ)²) cubed when the point lies beyond the mean
//    distance μ (r: from the probe to the point moved 0.25 spacings along its normal), floored
//    and crushed as in the paper: exactly the paper's weight divided by 1.2, so that it peaks at 1.
double leakWeight(const DistanceMapLayout& layout, const float* moments, const Eigen::Vector3d& probe,
                  const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double spacing);

}  // namespace baker
