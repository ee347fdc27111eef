#include "scene/SceneOptions.h"

#include <fmt/format.h>

#include <cmath>

#include "common/Error.h"
#include "images/RgbImage.h"

namespace baker {
namespace {

Eigen::Vector3f parseSky(const std::string& text) {
  const SettingError bad("sky", fmt::format("must be three finite non-negative numbers r,g,b, got \"{}\"", text));
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == ',') parts.emplace_back();
    else parts.back() += c;
  }
  if (parts.size() != 3) throw bad;
  Eigen::Vector3f rgb;
  for (int c = 0; c < 3; ++c) {
    std::size_t used = 0;
    try {
      rgb[c] = std::stof(parts[c], &used);
    } catch (const std::exception&) {
      throw bad;
    }
    if (used != parts[c].size() || !std::isfinite(rgb[c]) || rgb[c] < 0.0f) throw bad;
  }
  return rgb;
}

}  // namespace

Environment environmentFromOptions(const SceneOptions& options, std::vector<std::string>& warnings) {
  // Radiance is carried in single precision, so the multiplier must be a finite float too.
  if (!std::isfinite(float(options.environmentIntensity)) || options.environmentIntensity < 0.0)
    throw SettingError("env_intensity",
                       fmt::format("must be a finite non-negative number within single precision, got {}",
                                   options.environmentIntensity));
  if (!std::isfinite(options.environmentRotation))
    throw SettingError("env_rotation",
                       fmt::format("must be a finite number of degrees, got {}", options.environmentRotation));
  if (!options.environmentMap.empty() && !options.sky.empty())
    throw SettingError("sky", "and an environment map both describe the environment; give one of them");
  if (!options.sky.empty()) return Environment::constant(parseSky(options.sky));
  if (options.environmentMap.empty()) return Environment();
  RgbImage image = readRgbImage(options.environmentMap);
  Environment env = Environment::latLong(image.width, image.height, std::move(image.pixels),
                                         float(options.environmentIntensity), float(options.environmentRotation),
                                         options.environmentMap);
  if (env.sanitizedTexels() > 0)
    warnings.push_back(fmt::format("{}: {} texel(s) were negative or not finite and read as 0", options.environmentMap,
                                   env.sanitizedTexels()));
  return env;
}

}  // namespace baker
