#version 450 core
#extension GL_GOOGLE_include_directive : require
// Calls every function of baker_irradiance.glsl, so that compiling this shader (the ctest
// GlslDecoders.Compile, with glslangValidator) checks all of them. Not meant for rendering.
#include "baker_adaptive.glsl"
#include "baker_irradiance.glsl"

layout(binding = 0) uniform sampler3D shL1[3];
layout(binding = 3) uniform sampler3D shL2[7];
layout(binding = 10) uniform sampler3D ambientCube[5];
layout(binding = 15) uniform sampler3D ambientDice[9];
layout(binding = 24) uniform sampler3D ambientDiceYCoCg[15];
layout(binding = 39) uniform sampler3D visibility1[1];
layout(binding = 40) uniform sampler3D visibility2[2];
layout(binding = 42) uniform sampler3D visibility3[3];
layout(binding = 45) uniform sampler3D visibility9[9];

layout(location = 0) uniform vec3 origin;
layout(location = 1) uniform float spacing;
layout(location = 2) uniform ivec3 dims;

layout(binding = 54) uniform highp usampler3D indirection;
layout(binding = 55) uniform sampler3D pool[15];
layout(location = 3) uniform int levelCount;
layout(location = 4) uniform vec3 levelOrigin[BAKER_MAX_LEVELS];
layout(location = 8) uniform float levelSpacing[BAKER_MAX_LEVELS];
layout(location = 12) uniform ivec3 levelDims[BAKER_MAX_LEVELS];
layout(location = 16) uniform int levelBrickZ[BAKER_MAX_LEVELS];
layout(location = 20) uniform int slotsAcross;

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec4 color;

void main() {
  vec3 uvw = bakerVolumeCoordinate(worldPosition, origin, spacing, dims);
  vec3 n = normalize(normal);
  vec3 e = bakerSampleIrradianceShL1(shL1, uvw, n) + bakerSampleIrradianceShL2(shL2, uvw, n) +
           bakerSampleIrradianceAmbientCube(ambientCube, uvw, n) + bakerSampleIrradianceAdLinear(ambientDice, uvw, n) +
           bakerSampleIrradianceAdCos2(ambientDice, uvw, n) + bakerSampleIrradianceAdSrbf(ambientDice, uvw, n) +
           bakerSampleIrradianceAdYCoCg(ambientDiceYCoCg, uvw, n);
  float v = bakerSampleVisibilityShL1(visibility1, uvw, n) + bakerSampleVisibilityShL2(visibility3, uvw, n) +
            bakerSampleVisibilityAmbientCube(visibility2, uvw, n) + bakerSampleVisibilityAdLinear(visibility3, uvw, n) +
            bakerSampleVisibilityAdCos2(visibility3, uvw, n) + bakerSampleVisibilityAdSrbf(visibility3, uvw, n) +
            bakerSampleVisibilityAdYCoCg(visibility9, uvw, n);
  BakerCorners corners =
      bakerAdaptiveCorners(worldPosition, indirection, levelCount, levelOrigin, levelSpacing, levelDims, levelBrickZ);
  BAKER_ADAPTIVE_FETCH(pool, 15, corners, slotsAcross, adaptive);
  e += bakerIrradianceAdYCoCg(adaptive, n);
  color = vec4(e, v);
}
