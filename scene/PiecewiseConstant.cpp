#include "scene/PiecewiseConstant.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace baker {
namespace {

std::vector<double> rowSums(int columns, int rows, const std::vector<double>& weights) {
  if (columns <= 0 || rows <= 0 || weights.size() != std::size_t(columns) * rows)
    throw std::invalid_argument("PiecewiseConstant2D: weights do not match the grid");
  std::vector<double> sums(rows, 0.0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) sums[r] += weights[std::size_t(r) * columns + c];
  return sums;
}

}  // namespace

PiecewiseConstant1D::PiecewiseConstant1D(const std::vector<double>& weights) : cdf_(weights.size() + 1, 0.0) {
  if (weights.empty()) throw std::invalid_argument("PiecewiseConstant1D: no bins");
  for (std::size_t i = 0; i < weights.size(); ++i) {
    if (!(weights[i] >= 0.0)) throw std::invalid_argument("PiecewiseConstant1D: a weight is negative or NaN");
    cdf_[i + 1] = cdf_[i] + weights[i];
  }
  total_ = cdf_.back();
  if (total_ > 0.0)
    for (double& c : cdf_) c /= total_;
  // Exactly 1, so that every xi < 1 finds a bin.
  cdf_.back() = 1.0;
}

std::size_t PiecewiseConstant1D::sample(double xi, double* within) const {
  // The last entry not above xi starts the bin; equal entries (empty bins) are skipped.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end() - 1, xi);
  const std::size_t bin = std::size_t(std::max<std::ptrdiff_t>(it - cdf_.begin() - 1, 0));
  const double width = cdf_[bin + 1] - cdf_[bin];
  if (within) *within = width > 0.0 ? std::clamp((xi - cdf_[bin]) / width, 0.0, std::nextafter(1.0, 0.0)) : 0.0;
  return bin;
}

PiecewiseConstant2D::PiecewiseConstant2D(int columns, int rows, const std::vector<double>& weights)
    : marginal_(rowSums(columns, rows, weights)) {
  conditional_.reserve(rows);
  for (int r = 0; r < rows; ++r) {
    const auto first = weights.begin() + std::ptrdiff_t(r) * columns;
    conditional_.emplace_back(std::vector<double>(first, first + columns));
  }
}

void PiecewiseConstant2D::sample(double xiColumn, double xiRow, int* column, int* row, double* withinColumn,
                                 double* withinRow) const {
  *row = int(marginal_.sample(xiRow, withinRow));
  *column = int(conditional_[*row].sample(xiColumn, withinColumn));
}

}  // namespace baker
