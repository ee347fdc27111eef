#pragma once
#include <cstdint>

namespace baker {

// Which light-transport effects a bake simulates, decided from the scene (planTransport) and
// the user's `--no EFFECT` switches.
struct TransportSettings {
  bool emission = true;        // emissive surfaces seen directly by probe rays
  bool punctualLights = true;  // punctual lights lighting surfaces (next-event estimation)
  bool emissiveLights = true;  // emissive surfaces lighting other surfaces (sampled by power, MIS)
  bool environment = true;     // the sky: seen directly, and lighting surfaces (importance sampled, MIS)
  int bounces = 3;             // diffuse reflections per path; 0 when nothing reflects
  bool alphaFilters = true;    // MASK and BLEND surfaces let rays through
  bool directPunctual = true;  // punctual lights' own delta contribution to each probe
  bool probeValidity = true;   // probes inside geometry are detected, moved or filled
  std::uint64_t seed = 0;
};

// Rays traced by kind, for the bake summary.
struct RayCounts {
  std::int64_t probe = 0;             // from probes: radiance and sky visibility
  std::int64_t bounce = 0;            // continuing paths after a diffuse reflection
  std::int64_t punctualShadow = 0;    // towards punctual lights from surfaces
  std::int64_t emitterShadow = 0;     // towards sampled points of emissive triangles
  std::int64_t environmentShadow = 0; // towards sampled sky directions
  std::int64_t directPunctualShadow = 0;  // from probes towards punctual lights
  std::int64_t directView = 0;        // from probes: sampled sky directions, emitter points, aims near lights
  std::int64_t directViewShadow = 0;  // from the first hits of those aims towards their lights
  std::int64_t aimedBounce = 0;       // from path vertices, aimed near punctual lights
  std::int64_t aimedBounceShadow = 0; // from the first hits of those towards their lights
  std::int64_t validity = 0;          // testing whether probes sit inside geometry

  std::int64_t total() const {
    return probe + bounce + punctualShadow + emitterShadow + environmentShadow + directPunctualShadow + directView +
           directViewShadow + aimedBounce + aimedBounceShadow + validity;
  }
  RayCounts& operator+=(const RayCounts& o) {
    probe += o.probe;
    bounce += o.bounce;
    punctualShadow += o.punctualShadow;
    emitterShadow += o.emitterShadow;
    environmentShadow += o.environmentShadow;
    directPunctualShadow += o.directPunctualShadow;
    directView += o.directView;
    directViewShadow += o.directViewShadow;
    aimedBounce += o.aimedBounce;
    aimedBounceShadow += o.aimedBounceShadow;
    validity += o.validity;
    return *this;
  }
};

}  // namespace baker
