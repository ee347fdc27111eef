#pragma once
#include <string>
#include <vector>

#include "validate/LatLongEnvironment.h"

namespace baker {

// The three kinds of signal on the sphere a basis is judged on (Nielsen's thesis, §3.1): the
// radiance a probe sees, the irradiance it gives, and its self-occlusion (1 where a ray from the
// probe escapes the scene, 0 where it hits geometry).
enum class SignalKind { Radiance, Irradiance, Occlusion };
// SettingError("signal") for anything but radiance, irradiance or occlusion.
SignalKind parseSignalKind(const std::string& name);
const char* signalKindName(SignalKind kind);

// One test signal as a lat-long image at the evaluation's resolution. An occlusion signal is
// one channel, held in all three.
struct SphereSignal {
  std::string name;  // the file it came from, and for occlusion the probe's position
  LatLongEnvironment image;
  bool scalar = false;
};

// Width of every signal's image (height half of it): 8192 texels, enough for SH of order 8 and
// SG of 64 lobes to be fitted by least squares over the texels and few enough to fit 30 bases
// in seconds.
constexpr int kSignalWidth = 128;

// `image` averaged down to `width` × width/2 texels, each the solid-angle-weighted mean of the
// block of texels it covers. InputError naming `path` when the image is smaller than that or its
// size is not a multiple of it.
LatLongEnvironment areaDownsampled(const LatLongEnvironment& image, int width, const std::string& path);

// A light probe's radiance, or its exact irradiance (exactIrradiance of the downsampled radiance).
// InputError naming the file when it is black (a relative error needs a mean above zero).
SphereSignal environmentSignal(const std::string& path, SignalKind kind);

// Partly occluded spots only carry a self-occlusion signal: a probe that sees all sky or none is
// left out (a constant has no relative error).
constexpr double kMinOpenFraction = 0.02;

// The self-occlusion at each position the scene suggests for probes (scenes[i].extras.probe_hint)
// that sees between kMinOpenFraction and 1 − kMinOpenFraction of the sphere open; each position
// left out is added to `skipped` with its open fraction. InputError naming the file when it
// suggests no usable position.
std::vector<SphereSignal> occlusionSignals(const std::string& scenePath, std::vector<std::string>& skipped);

}  // namespace baker
