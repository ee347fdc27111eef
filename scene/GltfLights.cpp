#include "scene/GltfLights.h"

#include <fmt/format.h>

#include <cmath>

#include "common/Error.h"

namespace baker {

const char* lightTypeName(PunctualLight::Type type) {
  switch (type) {
    case PunctualLight::Type::Point: return "point";
    case PunctualLight::Type::Spot: return "spot";
    case PunctualLight::Type::Directional: break;
  }
  return "directional";
}

std::optional<PunctualLight> readLight(const tinygltf::Model& model, int node, const Eigen::Matrix4d& world,
                                       const std::string& file) {
  const auto ext = model.nodes[node].extensions.find("KHR_lights_punctual");
  if (ext == model.nodes[node].extensions.end()) return std::nullopt;
  const std::string nodePath = fmt::format("{}: nodes[{}].extensions.KHR_lights_punctual.light", file, node);
  if (!ext->second.Has("light") || !ext->second.Get("light").IsInt())
    throw InputError(fmt::format("{} must be a light index", nodePath));
  const int index = ext->second.Get("light").GetNumberAsInt();
  if (index < 0 || std::size_t(index) >= model.lights.size())
    throw InputError(fmt::format("{} refers to light {}, which does not exist ({} lights)", nodePath, index,
                                 model.lights.size()));
  const tinygltf::Light& src = model.lights[index];
  const std::string path = fmt::format("{}: extensions.KHR_lights_punctual.lights[{}]", file, index);
  auto fail = [&](const std::string& what) { throw InputError(fmt::format("{}{}", path, what)); };

  PunctualLight light;
  light.name = src.name;
  light.node = node;
  if (src.type == "point") light.type = PunctualLight::Type::Point;
  else if (src.type == "spot") light.type = PunctualLight::Type::Spot;
  else if (src.type == "directional") light.type = PunctualLight::Type::Directional;
  else fail(fmt::format(".type \"{}\" is not point, spot or directional", src.type));
  if (!src.color.empty()) {
    if (src.color.size() != 3) fail(".color must have 3 numbers");
    for (int c = 0; c < 3; ++c) light.color[c] = float(src.color[c]);
    if (!light.color.allFinite() || light.color.minCoeff() < 0.0f) fail(".color must be finite and non-negative");
  }
  if (!std::isfinite(src.intensity) || src.intensity < 0.0) fail(".intensity must be finite and non-negative");
  light.intensity = float(src.intensity);
  // Light is carried in single precision: beyond it, every path the light reaches becomes Inf.
  if (!std::isfinite(light.intensity) || !(light.color * light.intensity).allFinite())
    fail(fmt::format(".intensity {} times .color is beyond single precision", src.intensity));
  // tinygltf reads an absent range as 0; glTF requires range > 0, so 0 can only mean "none".
  if (!std::isfinite(src.range) || src.range < 0.0) fail(".range must be a positive number");
  if (src.range > 0.0) light.range = float(src.range);
  if (light.type == PunctualLight::Type::Spot) {
    const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
    if (!(inner >= 0.0 && inner <= outer && outer <= M_PI / 2))
      fail(fmt::format(".spot: innerConeAngle {} and outerConeAngle {} must satisfy 0 ≤ inner ≤ outer ≤ π/2", inner,
                       outer));
    light.innerConeAngle = float(inner);
    light.outerConeAngle = float(outer);
  }

  light.position = world.topRightCorner<3, 1>().cast<float>();
  // A point light has no direction, so only spot and directional lights need an axis that
  // survives the node's transform.
  const Eigen::Vector3d axis = world.topLeftCorner<3, 3>() * Eigen::Vector3d(0.0, 0.0, -1.0);
  if (light.type != PunctualLight::Type::Point && !(axis.norm() > 0.0))
    throw InputError(fmt::format("{}: nodes[{}] places light {} with a transform that collapses its direction", file,
                                 node, index));
  light.direction = axis.norm() > 0.0 ? axis.normalized().cast<float>() : Eigen::Vector3f(0.0f, 0.0f, -1.0f);
  return light;
}

}  // namespace baker
