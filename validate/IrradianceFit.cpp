#include "validate/IrradianceFit.h"

#include <algorithm>
#include <map>

#include "basis/GramOperators.h"
#include "basis/ProjectionOperator.h"
#include "validate/IrradianceReference.h"

namespace baker {
namespace {

Eigen::MatrixX3d reconstructAll(const Basis& basis, const std::vector<float>& coefficients,
                                const DirectionSet& directions) {
  Eigen::MatrixX3d values(directions.size(), 3);
  for (std::size_t t = 0; t < directions.size(); ++t)
    values.row(t) = basis.reconstruct(coefficients.data(), directions.directions[t]).cast<double>().transpose();
  return values;
}

IrradianceFit makeFit(const Basis& basis, std::string method, std::string description, std::vector<float> coefficients,
                      const DirectionSet& texels, const Eigen::MatrixX3d& reference) {
  IrradianceFit fit{std::move(method), std::move(description), std::move(coefficients), {}, 0.0, 0.0};
  fit.irradiance = reconstructAll(basis, fit.coefficients, texels);
  fit.rmse = irradianceRmse(fit.irradiance, reference);
  return fit;
}

// SH is projected exactly, as the paper does, rather than fitted.
std::vector<IrradianceFit> shFits(const Basis& basis, const DirectionSet& texels, const LatLongEnvironment& env,
                                  const Eigen::MatrixX3d& reference) {
  const SphericalFunctions& sh = basis.functions(0);
  const int n = sh.count();
  // Radiance moments by the texel sum: c = Yᵀ diag(ΔΩ) L.
  Eigen::MatrixXd weightedY(texels.size(), n);
  Eigen::VectorXd y(n);
  for (std::size_t t = 0; t < texels.size(); ++t) {
    sh.evaluate(texels.directions[t], y.data());
    weightedY.row(t) = texels.weights[t] * y.transpose();
  }
  const Eigen::MatrixXd radiance = weightedY.transpose() * env.radiance();  // n × 3
  std::vector<float> coefficients(3 * n);
  for (int l = 0; l * l < n; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i)
      for (int ch = 0; ch < 3; ++ch) coefficients[ch * n + i] = float(clampedCosineBand(l) * radiance(i, ch));

  std::vector<IrradianceFit> fits;
  fits.push_back(makeFit(basis, "unclamped", "SH projection by texel sum, cosine-convolved, unclamped",
                         std::move(coefficients), texels, reference));
  IrradianceFit clamped = fits.front();
  clamped.method = "clamped";
  clamped.description = "the same, negative irradiance clamped to 0";
  clamped.irradiance = clamped.irradiance.cwiseMax(0.0);
  clamped.rmse = irradianceRmse(clamped.irradiance, reference);
  fits.push_back(std::move(clamped));
  return fits;
}

IrradianceFit leastSquaresFit(const Basis& basis, const DirectionSet& samples, const DirectionSet& texels,
                              const Eigen::MatrixX3d& reference, std::string method, std::string description) {
  // The colour transform is linear with binary-fraction weights, so applying it to the unit
  // vectors gives its matrix exactly; the fit then stays in double precision.
  Eigen::Matrix3d toSpace;
  for (int c = 0; c < 3; ++c)
    toSpace.col(c) = toColorSpace(basis.colorSpace(), Eigen::Vector3f::Unit(c)).cast<double>();
  const Eigen::MatrixX3d target = reference * toSpace.transpose();

  std::map<const SphericalFunctions*, ProjectionOperator> operators;  // channels may share one set
  std::vector<float> coefficients(basis.totalCoefficients());
  double conditionNumber = 0.0;
  for (int c = 0; c < 3; ++c) {
    const SphericalFunctions& f = basis.functions(c);
    auto op = operators.find(&f);
    if (op == operators.end()) {
      op = operators.emplace(&f, leastSquaresProjection(f, samples, basis.name())).first;
      conditionNumber = std::max(conditionNumber, op->second.conditionNumber);
    }
    const Eigen::VectorXd channel = op->second.matrix * target.col(c);
    for (int i = 0; i < f.count(); ++i) coefficients[basis.coefficientOffset(c) + i] = float(channel[i]);
  }
  IrradianceFit fit =
      makeFit(basis, std::move(method), std::move(description), std::move(coefficients), texels, reference);
  fit.conditionNumber = conditionNumber;
  return fit;
}

}  // namespace

std::vector<IrradianceFit> fitIrradiance(const Basis& basis, const LatLongEnvironment& env,
                                         const Eigen::MatrixX3d& reference) {
  const DirectionSet texels = env.texels();
  if (basis.family() == "sh") return shFits(basis, texels, env, reference);

  DirectionSet uniform = texels;
  uniform.weights.assign(texels.size(), 4.0 * M_PI / double(texels.size()));
  std::vector<IrradianceFit> fits;
  fits.push_back(leastSquaresFit(basis, texels, texels, reference, "weighted_fit",
                                 "least squares fit to the exact irradiance, solid-angle weights"));
  fits.push_back(leastSquaresFit(basis, uniform, texels, reference, "unweighted_fit",
                                 "least squares fit to the exact irradiance, every texel weighted equally"));
  return fits;
}

}  // namespace baker
