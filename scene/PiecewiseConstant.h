#pragma once
#include <cstddef>
#include <vector>

namespace baker {

// A discrete distribution over bins with non-negative weights, sampled by inverting its
// cumulative sum. Built once; sampling is a binary search.
class PiecewiseConstant1D {
 public:
  explicit PiecewiseConstant1D(const std::vector<double>& weights);

  std::size_t size() const { return cdf_.size() - 1; }
  double total() const { return total_; }
  // The bin whose share of [0, 1) contains xi, and xi's position inside that share, in [0, 1).
  // Bins of zero weight are never returned. Requires total() > 0.
  std::size_t sample(double xi, double* within) const;
  double probability(std::size_t bin) const { return cdf_[bin + 1] - cdf_[bin]; }

 private:
  std::vector<double> cdf_;  // size() + 1 entries from 0 to 1
  double total_ = 0.0;
};

// A distribution over the cells of a rows × columns grid: a row from the marginal (row sums),
// then a column from that row's conditional.
class PiecewiseConstant2D {
 public:
  // `weights` row by row.
  PiecewiseConstant2D(int columns, int rows, const std::vector<double>& weights);

  double total() const { return marginal_.total(); }
  // Cell and positions within it (as PiecewiseConstant1D::sample). Requires total() > 0.
  void sample(double xiColumn, double xiRow, int* column, int* row, double* withinColumn, double* withinRow) const;

 private:
  std::vector<PiecewiseConstant1D> conditional_;
  PiecewiseConstant1D marginal_;
};

}  // namespace baker
