#include "basis/DiffuseResponse.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <mutex>

#include "basis/DirectionSet.h"
#include "basis/GramOperators.h"
#include "common/Error.h"

namespace baker {
namespace {

// (f_i)_lm · A_l to `order`: bands the clamped cosine zeroes (odd l > 1) are left out of the integration.
Eigen::MatrixXd responseInSh(const SphericalFunctions& functions, int order) {
  const SphericalHarmonics harmonics(order);
  const Eigen::MatrixXd moments = innerProducts(functions, harmonics);
  Eigen::MatrixXd response = Eigen::MatrixXd::Zero(moments.rows(), moments.cols());
  for (int l = 0; l <= order; ++l) {
    const double a = clampedCosineBand(l);
    if (a == 0.0) continue;
    response.middleCols(l * l, 2 * l + 1) = moments.middleCols(l * l, 2 * l + 1) * a;
  }
  return response;
}

// The responses at well-spread normals, one column each.
Eigen::MatrixXd responsesAt(const Eigen::MatrixXd& response, const DirectionSet& normals) {
  const int order = int(std::lround(std::sqrt(double(response.cols())))) - 1;
  const SphericalHarmonics harmonics(order);
  Eigen::MatrixXd y(response.cols(), Eigen::Index(normals.size()));
  for (std::size_t k = 0; k < normals.size(); ++k) harmonics.evaluate(normals.directions[k], y.col(Eigen::Index(k)).data());
  return response * y;
}

}  // namespace

DiffuseResponse::DiffuseResponse(const SphericalFunctions& functions, const std::string& label) {
  if (const std::optional<RadialLobes> lobes = functions.radialLobes()) {
    radial_.emplace(lobes->profile, label);
    axes_ = lobes->axes;
    return;
  }
  isSh_ = functions.shBands() >= 0;
  const int degree = functions.polynomialDegree();
  if (degree >= 0) {
    // A polynomial of degree d has no moment above band d: the sum is exact there.
    fromSh_ = responseInSh(functions, degree);
    harmonics_ = SphericalHarmonics(degree);
    return;
  }
  const DirectionSet normals = sphericalFibonacci(512);
  Eigen::MatrixXd previousValues = responsesAt(responseInSh(functions, 8), normals);
  for (int order = 16; order <= SphericalHarmonics::kMaxOrder; order += 8) {
    Eigen::MatrixXd next = responseInSh(functions, order);
    const Eigen::MatrixXd values = responsesAt(next, normals);
    if ((values - previousValues).cwiseAbs().maxCoeff() <= 1e-6 * values.cwiseAbs().maxCoeff()) {
      fromSh_ = std::move(next);
      harmonics_ = SphericalHarmonics(order);
      return;
    }
    previousValues = values;
  }
  throw NumericalError(fmt::format("{}: the diffuse response of its functions has not converged at SH order {}", label,
                                   SphericalHarmonics::kMaxOrder));
}

void DiffuseResponse::evaluate(const Eigen::Vector3d& normal, double* response) const {
  if (radial_) {
    for (std::size_t i = 0; i < axes_.size(); ++i) response[i] = (*radial_)(axes_[i].dot(normal));
    return;
  }
  thread_local Eigen::VectorXd y;
  y.resize(harmonics_.count());
  harmonics_.evaluate(normal, y.data());
  Eigen::Map<Eigen::VectorXd>(response, count()) = fromSh_ * y;
}

nlohmann::json DiffuseResponse::describe() const {
  if (radial_)
    return {{"type", "legendre"},
            {"coefficients", radial_->coefficients()},
            {"formula", "K_i(n) = sum over l of coefficients[l] P_l(axis_i . n), P_l the Legendre polynomials"}};
  if (!isSh_) return nullptr;
  std::vector<double> bands;
  for (int l = 0; l <= harmonics_.order(); ++l) bands.push_back(clampedCosineBand(l));
  return {{"type", "band-factors"},
          {"coefficients", bands},
          {"formula", "E(n) = sum over l, m of coefficients[l] c_lm Y_lm(n)"}};
}

std::shared_ptr<const DiffuseResponse> diffuseResponseOf(const Basis& basis, int channel) {
  int first = channel;
  while (first > 0 && &basis.functions(first - 1) == &basis.functions(channel)) first -= 1;
  const std::string key = fmt::format("{}/{}", basis.identity(), first);
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const DiffuseResponse>> built;
  const std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<const DiffuseResponse>& response = built[key];
  if (!response) response = std::make_shared<const DiffuseResponse>(basis.functions(channel), basis.name());
  return response;
}

}  // namespace baker
