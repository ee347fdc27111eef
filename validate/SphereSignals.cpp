#include "validate/SphereSignals.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <memory>

#include "common/Error.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "validate/IrradianceReference.h"

namespace baker {

SignalKind parseSignalKind(const std::string& name) {
  if (name == "radiance") return SignalKind::Radiance;
  if (name == "irradiance") return SignalKind::Irradiance;
  if (name == "occlusion") return SignalKind::Occlusion;
  throw SettingError("signal", fmt::format("\"{}\": expected radiance, irradiance or occlusion", name));
}

const char* signalKindName(SignalKind kind) {
  switch (kind) {
    case SignalKind::Radiance: return "radiance";
    case SignalKind::Irradiance: return "irradiance";
    case SignalKind::Occlusion: return "occlusion";
  }
  return "";
}

LatLongEnvironment areaDownsampled(const LatLongEnvironment& image, int width, const std::string& path) {
  const int height = width / 2;
  if (image.width() < width || image.height() < height || image.width() % width != 0 || image.height() % height != 0 ||
      image.width() / width != image.height() / height)
    throw InputError(fmt::format("{}: {} × {} texels; an evaluation signal needs a lat-long image whose size is a "
                                 "multiple of {} × {}",
                                 path, image.width(), image.height(), width, height));
  const int factor = image.width() / width;
  Eigen::MatrixX3d radiance = Eigen::MatrixX3d::Zero(std::int64_t(width) * height, 3);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      double area = 0.0;
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      for (int r = row * factor; r < (row + 1) * factor; ++r)
        for (int c = column * factor; c < (column + 1) * factor; ++c) {
          const double w = image.texelSolidAngle(r);
          sum += w * image.radiance().row(std::int64_t(r) * image.width() + c);
          area += w;
        }
      radiance.row(std::int64_t(row) * width + column) = sum / area;
    }
  return LatLongEnvironment(width, height, std::move(radiance));
}

SphereSignal environmentSignal(const std::string& path, SignalKind kind) {
  LatLongEnvironment radiance = areaDownsampled(LatLongEnvironment::load(path), kSignalWidth, path);
  if (!(radiance.radiance().sum() > 0.0))
    throw InputError(fmt::format("{}: every texel is black; a relative error needs a signal above zero", path));
  if (kind == SignalKind::Irradiance) {
    Eigen::MatrixX3d irradiance = exactIrradiance(radiance);
    return {path, LatLongEnvironment(radiance.width(), radiance.height(), std::move(irradiance)), false};
  }
  return {path, std::move(radiance), false};
}

namespace {

// Traced at the texel centres themselves, so that the signal is exact where the fit is scored.
LatLongEnvironment openSky(const RayTracer& tracer, const Eigen::Vector3f& position) {
  const int width = kSignalWidth, height = kSignalWidth / 2;
  const LatLongEnvironment layout(width, height, Eigen::MatrixX3d::Zero(std::int64_t(width) * height, 3));
  Eigen::MatrixX3d open(std::int64_t(width) * height, 3);
  tbb::parallel_for(0, height, [&](int row) {
    std::vector<Ray> rays(static_cast<std::size_t>(width));
    std::unique_ptr<bool[]> blocked(new bool[std::size_t(width)]);
    for (int column = 0; column < width; ++column) {
      rays[std::size_t(column)].origin = position;
      rays[std::size_t(column)].direction = layout.direction(row, column).cast<float>();
    }
    tracer.occluded(rays.data(), width, blocked.get());
    for (int column = 0; column < width; ++column)
      open.row(std::int64_t(row) * width + column).setConstant(blocked[std::size_t(column)] ? 0.0 : 1.0);
  });
  return LatLongEnvironment(width, height, std::move(open));
}

}  // namespace

std::vector<SphereSignal> occlusionSignals(const std::string& scenePath, std::vector<std::string>& skipped) {
  const Scene scene = loadGltf(scenePath);
  if (scene.probeHints.empty()) {
    std::string why;
    for (const std::string& w : scene.warnings)
      if (w.find("probe_hint") != std::string::npos) why += "; " + w;
    throw InputError(fmt::format("{}: the scene suggests no probe position (scenes[i].extras.probe_hint); an occlusion "
                                 "signal is taken at each one{}",
                                 scenePath, why));
  }
  const RayTracer tracer(scene);
  std::vector<SphereSignal> signals;
  for (const Eigen::Vector3f& position : scene.probeHints) {
    LatLongEnvironment image = openSky(tracer, position);
    const DirectionSet texels = image.texels();
    double open = 0.0;
    for (std::size_t t = 0; t < texels.size(); ++t) open += texels.weights[t] * image.radiance()(std::int64_t(t), 0);
    open /= 4.0 * M_PI;
    std::string name = fmt::format("{} at ({}, {}, {})", scenePath, position.x(), position.y(), position.z());
    if (open < kMinOpenFraction || open > 1.0 - kMinOpenFraction) {
      skipped.push_back(fmt::format("{} (open {:.3g} of the sphere)", name, open));
      continue;
    }
    signals.push_back({std::move(name), std::move(image), true});
  }
  return signals;
}

}  // namespace baker
