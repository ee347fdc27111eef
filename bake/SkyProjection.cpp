#include "bake/SkyProjection.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "common/Error.h"
#include "common/FileHash.h"

namespace baker {

SkyRadiance recordSky(const Environment& environment) {
  SkyRadiance sky;
  switch (environment.kind()) {
    case Environment::Kind::None: return sky;
    case Environment::Kind::Constant:
      for (std::size_t t = 0; t < sky.rgb.size() / 3; ++t)
        for (int c = 0; c < 3; ++c) sky.rgb[3 * t + std::size_t(c)] = environment.constantRadiance()[c];
      return sky;
    case Environment::Kind::Map: break;
  }
  // Each texel is cut into sub-cells no wider than half a record texel, each adding its flux to the
  // record texel its centre falls in: a coarse map's texels are spread over the record's, never
  // dropped on a shared edge.
  const int columnsPerTexel = std::max(1, (2 * sky.width + environment.width() - 1) / environment.width());
  const int rowsPerTexel = std::max(1, (2 * sky.height + environment.height() - 1) / environment.height());
  const double du = 1.0 / (double(environment.width()) * columnsPerTexel);
  const double dv = 1.0 / (double(environment.height()) * rowsPerTexel);
  std::vector<double> flux(sky.rgb.size(), 0.0);
  for (int row = 0; row < environment.height() * rowsPerTexel; ++row) {
    const double v = row * dv, solidAngle = latLongSolidAngle(du, v, v + dv);
    for (int column = 0; column < environment.width() * columnsPerTexel; ++column) {
      const Eigen::Vector3d radiance =
          environment.texelRadiance(column / columnsPerTexel, row / rowsPerTexel).cast<double>() * solidAngle;
      const Eigen::Vector2i t =
          skyTexelOf(environment.directionAt((column + 0.5) * du, v + 0.5 * dv), sky.width, sky.height);
      for (int c = 0; c < 3; ++c) flux[3 * (std::size_t(t.y()) * sky.width + t.x()) + c] += radiance[c];
    }
  }
  for (int row = 0; row < sky.height; ++row) {
    const double solidAngle = latLongSolidAngle(1.0 / sky.width, double(row) / sky.height, double(row + 1) / sky.height);
    for (int column = 0; column < sky.width; ++column)
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = 3 * (std::size_t(row) * sky.width + column) + c;
        sky.rgb[i] = float(flux[i] / solidAngle);
        if (!std::isfinite(sky.rgb[i]))
          throw InputError(fmt::format("{}: its light, gathered into the volume's {} x {} sky, leaves single precision "
                                       "(texel {}, {}); lower its intensity",
                                       environment.source(), sky.width, sky.height, column, row));
      }
  }
  return sky;
}

std::string skyDescription(const Environment& environment) {
  switch (environment.kind()) {
    case Environment::Kind::None: return "none";
    case Environment::Kind::Constant: {
      const Eigen::Vector3f& c = environment.constantRadiance();
      return fmt::format("constant {},{},{}", c.x(), c.y(), c.z());
    }
    case Environment::Kind::Map: break;
  }
  return fmt::format("map {} fnv1a64 {} intensity {} rotation {}",
                     std::filesystem::path(environment.source()).filename().string(), fileHash(environment.source()),
                     environment.intensity(), environment.rotationDegrees());
}

}  // namespace baker
