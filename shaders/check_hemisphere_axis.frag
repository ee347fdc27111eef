#version 450 core
#extension GL_GOOGLE_include_directive : require
// ad-hemi9 baked about an axis other than +Y: its nine "axes" from the file in a uniform, named
// by BAKER_AD_HEMI9_AXES before the include (ctest GlslDecoders.CompileHemisphereAxis). Not
// meant for rendering.
layout(location = 0) uniform vec3 hemisphereAxes[9];
#define BAKER_AD_HEMI9_AXES hemisphereAxes
#include "baker_irradiance.glsl"

layout(binding = 0) uniform sampler3D radiance[7];
layout(binding = 7) uniform sampler3D visibility[3];
layout(binding = 10) uniform sampler2D specularBlend;
layout(location = 9) uniform vec3 uvw;
layout(location = 10) uniform float roughness;

layout(location = 0) in vec3 normal;
layout(location = 1) in vec3 toEye;
layout(location = 0) out vec4 color;

void main() {
  vec3 n = normalize(normal);
  vec4 t[7];
  for (int i = 0; i < 7; ++i) t[i] = texture(radiance[i], uvw);
  vec4 v[3];
  for (int i = 0; i < 3; ++i) v[i] = texture(visibility[i], uvw);
  vec4 s = bakerSpecularAdHemi9(t, n, normalize(toEye), roughness, specularBlend);
  color = vec4(bakerIrradianceFromRadianceAdHemi9(t, n) + s.rgb * s.a, bakerVisibilityFromRadianceAdHemi9(v, n));
}
