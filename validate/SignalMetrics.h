#pragma once
#include <Eigen/Core>
#include <string>

#include "validate/SignalFit.h"
#include "validate/SphereSignals.h"

namespace baker {

// How a reconstruction is scored against its signal (Nielsen's thesis, §3.4; docs/BASES.md):
//  - rmae: Σ|y − x| / Σ y over the signal's texels (each weighted alike, as the thesis' samples)
//    and channels (one for occlusion): the thesis' eq. in §3.4.1, lower is better;
//  - rmse: √(mean (y − x)²) / mean y over the same texels and channels, lower is better;
//  - ssim: the structural similarity of the six views along the axes (90° cube faces of
//    kSsimFaceSize² pixels, the projection the thesis uses because engines look up probes so),
//    on luminance after tone mapping (radiance and irradiance: exposure taking the signal's mean
//    luminance to 0.18, then x/(1 + x) per channel; occlusion: clamped to [0, 1]), with a
//    Gaussian window of σ = 1.5 pixels over 11 × 11 within each face, K1 = 0.01, K2 = 0.03 and
//    L = 1 (Wang et al. 2004); the mean over every window, higher is better.
enum class SignalMetric { Rmae, Rmse, Ssim };
// SettingError("metric") for anything but rmae, rmse or ssim.
SignalMetric parseSignalMetric(const std::string& name);
const char* signalMetricName(SignalMetric metric);
bool higherIsBetter(SignalMetric metric);

constexpr int kSsimFaceSize = 64;

double signalScore(const SphereSignal& signal, const FittedSignal& fit, SignalMetric metric);

// The pieces, exposed for tests. `reference` and `reconstruction` hold one row per texel.
double relativeMeanAbsoluteError(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& reconstruction, int channels);
double relativeRootMeanSquareError(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& reconstruction,
                                   int channels);
// The mean SSIM of two equally sized images (each face of the cube is scored on its own).
double structuralSimilarity(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace baker
