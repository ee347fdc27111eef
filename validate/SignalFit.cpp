#include "validate/SignalFit.h"

#include <map>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"
#include "basis/NonNegativeProjection.h"

namespace baker {

const char* fitMethodName(FitMethod method) { return method == FitMethod::Linear ? "linear" : "non_negative"; }

bool fitApplies(const Basis& basis, FitMethod method) {
  return method == FitMethod::Linear || admitsNonNegativeFit(basis);
}

namespace {

// The weighted normal equations of one function set over the texels: G = BᵀWB and the moments
// BᵀW of every column of `values`.
struct NormalEquations {
  Eigen::MatrixXd gram, inverse;
  Eigen::MatrixXd moments;  // functions × columns
};

// NumericalError naming `label` when the texels cannot tell the functions apart.
NormalEquations normalEquations(const SphericalFunctions& f, const DirectionSet& texels, const Eigen::MatrixXd& values,
                                const std::string& label) {
  Eigen::MatrixXd weighted(f.count(), texels.size()), basis(texels.size(), f.count());
  Eigen::VectorXd row(f.count());
  for (std::size_t t = 0; t < texels.size(); ++t) {
    f.evaluate(texels.directions[t], row.data());
    basis.row(std::int64_t(t)) = row.transpose();
    weighted.col(std::int64_t(t)) = texels.weights[t] * row;
  }
  NormalEquations e{weighted * basis, {}, weighted * values};
  e.inverse = invertSymmetric(e.gram, label + " (least squares over the signal's texels)", nullptr);
  return e;
}

}  // namespace

FittedSignal::FittedSignal(const Basis& basis, const SphereSignal& signal, FitMethod method)
    : basis_(basis), scalar_(signal.scalar), coefficients_(std::size_t(basis.totalCoefficients()), 0.0f) {
  const DirectionSet texels = signal.image.texels();
  Eigen::Matrix3d toSpace;  // exact: the colour transforms have binary-fraction weights
  for (int c = 0; c < 3; ++c)
    toSpace.col(c) = toColorSpace(basis.colorSpace(), Eigen::Vector3f::Unit(c)).cast<double>();
  const Eigen::MatrixX3d target = scalar_ ? signal.image.radiance() : Eigen::MatrixX3d(signal.image.radiance() * toSpace.transpose());
  const int channels = scalar_ ? 1 : 3;
  std::map<const SphericalFunctions*, NormalEquations> equations;  // channels may share a set
  for (int c = 0; c < channels; ++c) {
    // A hemispherical basis is fitted over its hemisphere only, as a bake fits it.
    const SphericalFunctions& f = basis.fitFunctions(c);
    auto found = equations.find(&f);
    if (found == equations.end()) found = equations.emplace(&f, normalEquations(f, texels, target, basis.name())).first;
    const NormalEquations& e = found->second;
    const bool constrained = method == FitMethod::NonNegative && !(basis.colorSpace() == ColorSpace::YCoCg && c > 0);
    const Eigen::VectorXd fitted = constrained ? nonNegativeProjection(e.gram, e.moments.col(c))
                                               : Eigen::VectorXd(e.inverse * e.moments.col(c));
    for (int i = 0; i < f.count(); ++i) coefficients_[std::size_t(basis.coefficientOffset(c) + i)] = float(fitted[i]);
    storedCoefficients_ += f.count();
  }
}

Eigen::Vector3d FittedSignal::at(const Eigen::Vector3d& d) const {
  if (!scalar_) return basis_.reconstruct(coefficients_.data(), d).cast<double>();
  const SphericalFunctions& f = basis_.functions(0);
  Eigen::VectorXd values(f.count());
  f.evaluate(d, values.data());
  const double v = values.dot(Eigen::Map<const Eigen::VectorXf>(coefficients_.data(), f.count()).cast<double>());
  return Eigen::Vector3d::Constant(v);
}

Eigen::MatrixX3d FittedSignal::atTexels(const LatLongEnvironment& layout) const {
  Eigen::MatrixX3d values(layout.texelCount(), 3);
  for (int row = 0; row < layout.height(); ++row)
    for (int column = 0; column < layout.width(); ++column)
      values.row(std::int64_t(row) * layout.width() + column) = at(layout.direction(row, column)).transpose();
  return values;
}

}  // namespace baker
