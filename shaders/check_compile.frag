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
layout(binding = 70) uniform sampler2D specularBlend;
layout(location = 21) uniform vec3 view;
layout(location = 22) uniform float roughness;
layout(location = 23) uniform vec3 sky[9];

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

  // Radiance volumes: the same packing, read through the radiance functions.
  BAKER_FETCH(shL1, 3, uvw, l1);
  BAKER_FETCH(shL2, 7, uvw, l2);
  BAKER_FETCH(ambientCube, 5, uvw, cube);
  BAKER_FETCH(ambientDice, 9, uvw, dice);
  BAKER_FETCH(visibility1, 1, uvw, v1);
  BAKER_FETCH(visibility2, 2, uvw, v2);
  BAKER_FETCH(visibility3, 3, uvw, v3);
  e += bakerIrradianceFromRadianceShL1(l1, n) + bakerIrradianceFromRadianceShL2(l2, n) +
       bakerIrradianceFromRadianceAmbientCube(cube, n) + bakerIrradianceFromRadianceAdCos2(dice, n) +
       bakerIrradianceFromRadianceAdSrbf(dice, n) + bakerIrradianceFromRadianceAdHemi9(l2, n) + bakerRadianceAdHemi9(l2, n);
  v += bakerVisibilityFromRadianceShL1(v1, n) + bakerVisibilityFromRadianceShL2(v3, n) +
       bakerVisibilityFromRadianceAmbientCube(v2, n) + bakerVisibilityFromRadianceAdCos2(v3, n) +
       bakerVisibilityFromRadianceAdSrbf(v3, n) + bakerVisibilityFromRadianceAdHemi9(v3, n);
  vec4 s = bakerSpecularShL1(l1, n, view, roughness, specularBlend) + bakerSpecularShL2(l2, n, view, roughness, specularBlend) +
           bakerSpecularAmbientCube(cube, n, view, roughness, specularBlend) +
           bakerSpecularAdCos2(dice, n, view, roughness, specularBlend) +
           bakerSpecularAdSrbf(dice, n, view, roughness, specularBlend) +
           bakerSpecularAdHemi9(l2, n, view, roughness, specularBlend);
  float leak = bakerLeakWeight(specularBlend, ivec2(8, 16), 8, 2.0 * spacing, origin, origin + n, n, spacing);
  e = bakerRelitIrradiance(e, v, sky, n);
  color = vec4(e + s.rgb * s.a, v * leak);
}
