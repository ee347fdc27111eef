#include "validate/IrradianceReference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace baker {

Eigen::MatrixX3d exactIrradiance(const LatLongEnvironment& env) {
  const int width = env.width(), height = env.height();
  // The clamped cosine between texel (i, j) and texel (r, c) depends only on the rows and on
  // the column offset k = c − j (mod width): n·ω = sin φ_i sin φ_r cos(2πk/width) + cos φ_i cos φ_r.
  // So for each source row r the sum is a product of the row's circulant data matrix,
  // C_r(ch·width + j, k) = L(r, j + k, ch), with the kernel K_r(k, i) = ΔΩ_r max(0, n·ω):
  // E(ch·width + j, i) = Σ_r (C_r K_r)(ch·width + j, i). Dense products run near peak speed,
  // unlike a texel-pair loop, and the arithmetic is the plain double-precision sum.
  std::vector<double> sinPolar(height), cosPolar(height), cosOffset(width);
  for (int r = 0; r < height; ++r) {
    sinPolar[r] = std::sin(env.polarAngle(r));
    cosPolar[r] = std::cos(env.polarAngle(r));
  }
  for (int k = 0; k < width; ++k) cosOffset[k] = std::cos(2.0 * M_PI * k / width);
  const Eigen::MatrixX3d& radiance = env.radiance();

  const auto addRows = [&](const tbb::blocked_range<int>& rows, Eigen::MatrixXd sum) {
    Eigen::MatrixXd data(3 * width, width), kernel(width, height);
    for (int r = rows.begin(); r != rows.end(); ++r) {
      for (int k = 0; k < width; ++k)
        for (int ch = 0; ch < 3; ++ch)
          for (int j = 0; j < width; ++j) data(ch * width + j, k) = radiance(Eigen::Index(r) * width + (j + k) % width, ch);
      const double solidAngle = env.texelSolidAngle(r);
      for (int i = 0; i < height; ++i)
        for (int k = 0; k < width; ++k)
          kernel(k, i) = solidAngle * std::max(0.0, sinPolar[i] * sinPolar[r] * cosOffset[k] + cosPolar[i] * cosPolar[r]);
      sum.noalias() += data * kernel;
    }
    return sum;
  };
  // Deterministic reduction: the same rounding whatever the number of threads.
  const Eigen::MatrixXd sum = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(0, height, 8), Eigen::MatrixXd::Zero(3 * width, height).eval(), addRows,
      [](Eigen::MatrixXd a, const Eigen::MatrixXd& b) {
        a += b;
        return a;
      });

  Eigen::MatrixX3d irradiance(env.texelCount(), 3);
  for (int i = 0; i < height; ++i)
    for (int j = 0; j < width; ++j)
      for (int ch = 0; ch < 3; ++ch) irradiance(Eigen::Index(i) * width + j, ch) = sum(ch * width + j, i);
  return irradiance;
}

double irradianceRmse(const Eigen::MatrixX3d& irradiance, const Eigen::MatrixX3d& reference) {
  if (irradiance.rows() != reference.rows() || reference.rows() == 0)
    throw std::invalid_argument("irradiance RMSE: images of different sizes");
  // Mean over channels of per-channel mean squared errors = mean over all values.
  return std::sqrt((irradiance - reference).squaredNorm() / double(reference.size())) / M_PI;
}

}  // namespace baker
