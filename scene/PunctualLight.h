#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace baker {

// A KHR_lights_punctual light placed by its node. Numbers are glTF's, used as they are (see
// ../shared/tools/README.md): a point or spot light of intensity I and colour c gives
// E = c·I·cosθ/d² at distance d; a directional light gives E = c·I on a surface facing it.
struct PunctualLight {
  enum class Type { Point, Spot, Directional };

  Type type = Type::Point;
  std::string name;
  int node = -1;  // the glTF node that places it
  Eigen::Vector3f color{1.0f, 1.0f, 1.0f};
  float intensity = 1.0f;
  // glTF's range (point and spot); infinity when the file gives none. Kept for engines; the
  // reference renderer ignores it.
  float range = std::numeric_limits<float>::infinity();
  float innerConeAngle = 0.0f;                  // spot, radians from the axis
  float outerConeAngle = float(M_PI) / 4.0f;    // spot
  Eigen::Vector3f position{0.0f, 0.0f, 0.0f};   // world; point and spot
  Eigen::Vector3f direction{0.0f, 0.0f, -1.0f}; // world unit vector the light shines along: the node's −Z

  // The spot cone's attenuation for a point at angle a from the axis (cosAngle = cos a), the
  // KHR_lights_punctual implementation note's smooth falloff: t = (cos a − cos outer) /
  // (cos inner − cos outer) clamped to [0, 1], squared. The 1e-3 floor keeps a hard-edged cone
  // (inner = outer) finite, as the reference renderer does.
  float spotFalloff(float cosAngle) const {
    const float cosOuter = std::cos(outerConeAngle), cosInner = std::cos(innerConeAngle);
    const float t = std::clamp((cosAngle - cosOuter) / std::max(1e-3f, cosInner - cosOuter), 0.0f, 1.0f);
    return t * t;
  }
};

const char* lightTypeName(PunctualLight::Type type);

}  // namespace baker
