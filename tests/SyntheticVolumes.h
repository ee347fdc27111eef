#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "images/RgbImage.h"
#include "volume/Volume.h"

namespace baker::test {

// The values smoothVolume gives a probe at world position x (sh-l2: 27 coefficients and the
// visibility's first two).
void smoothProbe(const Basis& basis, const Eigen::Vector3d& x, float* coefficients, float* visibility);

// An sh-l2 volume whose irradiance is mostly constant with a gentle lobe, every coefficient an
// affine function of the probe's world position: trilinear sampling reproduces it exactly, so a
// volume on another grid over the same field compares at rounding error. All probes valid.
Volume smoothVolume(const Eigen::Vector3i& dims, const Eigen::Vector3d& origin, double spacing);

// Writes what reference_probe.py writes: DIR/probes.json (settings with `bounces`, the probes'
// positions and files) and DIR/probe_NNNN.exr, one copy of `panorama` per position.
void writeReferenceDirectory(const std::string& dir, const std::vector<Eigen::Vector3d>& positions,
                             const RgbImage& panorama, int bounces);

// A W × H panorama of constant radiance.
RgbImage constantPanorama(int width, int height, const Eigen::Vector3f& radiance);

}  // namespace baker::test
