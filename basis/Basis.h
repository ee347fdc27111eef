#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>

#include "basis/BasisParameters.h"
#include "basis/SphericalFunctions.h"

namespace baker {

enum class ColorSpace { Rgb, YCoCg };

const char* colorSpaceName(ColorSpace space);
// Names of the three channels in that colour space, e.g. {"Y", "Co", "Cg"}.
const char* channelName(ColorSpace space, int channel);
Eigen::Vector3f toColorSpace(ColorSpace space, const Eigen::Vector3f& rgb);
Eigen::Vector3f toRgb(ColorSpace space, const Eigen::Vector3f& color);

// A representation of RGB signals on the sphere. Each of the three channels of the basis's
// colour space is expanded in its own set of functions (channels may share one set), so a
// probe stores, channel after channel, coefficientCount(c) numbers per channel c.
class Basis {
 public:
  virtual ~Basis() = default;
  virtual std::string name() const = 0;
  // What a reader dispatches on: "sh", "ambient-dice", "ambient-cube", "spherical-gaussians".
  virtual std::string family() const = 0;
  // What the name leaves open, with the values this basis uses (e.g. sg-N's sharpness): given to
  // makeBasis with the name, they make the same basis.
  virtual BasisParameters parameters() const { return {}; }
  virtual ColorSpace colorSpace() const { return ColorSpace::Rgb; }
  virtual const SphericalFunctions& functions(int channel) const = 0;
  // What a bake fits the samples with, when it is not functions(): a hemispherical basis fits
  // its functions cut off at the horizon, and is read with them whole.
  virtual const SphericalFunctions& fitFunctions(int channel) const { return functions(channel); }
  // The axis of the hemisphere a basis holds radiance over, when it holds only that: it is baked
  // with --signal radiance only, and read for normals about that axis.
  virtual std::optional<Eigen::Vector3d> hemisphere() const { return std::nullopt; }
  // How many stored coefficients (all channels) reconstructing one direction reads.
  virtual int coefficientsPerLookup() const = 0;

  // The signal (in RGB) in direction `d` from one probe's coefficients, laid out as
  // described above. The default evaluates every function; bases with local support
  // override it to read only coefficientsPerLookup() values.
  virtual Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const;

  // The name and the parameters() that tell this basis from another of the same name: a key
  // for what is built once per basis.
  std::string identity() const;

  int coefficientCount(int channel) const { return functions(channel).count(); }
  int coefficientOffset(int channel) const;
  int totalCoefficients() const { return coefficientOffset(3); }
  // True when R, G and B (or Y, Co, Cg) use one and the same function set.
  bool channelsShareFunctions() const;
};

}  // namespace baker
