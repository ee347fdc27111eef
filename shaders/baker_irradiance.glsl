// baker_irradiance.glsl — GLSL 4.50 decoders for baker irradiance volumes. No #version line:
// paste or include it after the shader's own ("#version 450 core").
//
// Packing (docs/DECODERS.md): a probe's stored numbers, in the file's order (channel after
// channel: R, G, B or Y, Co, Cg; coefficient NN of channel c is component c of grid rgb_NN, or
// grid Y_NN / Co_NN / Cg_NN), four per RGBA texel: 3D texture k holds numbers 4k .. 4k+3, the
// last one padded with 0. Sky visibility (grids visibility_NN) is packed the same way into its
// own textures. Texel (i, j, k) of every texture is probe (i, j, k); filter GL_LINEAR, wrap
// GL_CLAMP_TO_EDGE, no mipmaps. Interpolating coefficients interpolates the irradiance, since
// reconstruction is linear in them, so one hardware trilinear fetch per texture gives the
// coefficients at any point.
//
// bakerIrradianceX(texels, n) decodes texels already fetched (one probe, or an interpolated
// one); bakerSampleIrradianceX(textures, uvw, n) fetches them first. Results are the full
// irradiance E(n) = ∫ L max(0, n·ω) dω: multiply by albedo/π for diffuse radiance. n must be
// unit length. Texture counts: sh-l1 3, sh-l2 7, ambient-cube 5, ad-linear / ad-cos2 / ad-srbf
// 9, ad-ycocg 15; visibility: sh-l1 1, sh-l2 3, ambient-cube 2, ad-* 3, ad-ycocg 9.

// Texture coordinate of a world position: probe (i, j, k) sits at origin + spacing·(i, j, k),
// the centre of texel (i, j, k).
vec3 bakerVolumeCoordinate(vec3 worldPosition, vec3 origin, float spacing, ivec3 dims) {
  return ((worldPosition - origin) / spacing + 0.5) / vec3(dims);
}

// ---- Real spherical harmonics: orthonormal, polar axis z, no Condon–Shortley phase, index
// l·l + l + m (Y(1,−1) ∝ y, Y(1,0) ∝ z, Y(1,1) ∝ x).

vec4 bakerShL1Basis(vec3 n) { return vec4(0.282094792, 0.488602512 * n.y, 0.488602512 * n.z, 0.488602512 * n.x); }

void bakerShL2Basis(vec3 n, out float y[9]) {
  vec4 bands01 = bakerShL1Basis(n);
  for (int i = 0; i < 4; ++i) y[i] = bands01[i];
  y[4] = 1.092548431 * n.x * n.y;
  y[5] = 1.092548431 * n.y * n.z;
  y[6] = 0.315391565 * (3.0 * n.z * n.z - 1.0);
  y[7] = 1.092548431 * n.x * n.z;
  y[8] = 0.546274215 * (n.x * n.x - n.y * n.y);
}

// ---- Relighting at run time (docs/RELIGHTING.md): pack textures of the coefficients less the
// sky_direct grids' (the light that is not the sky's) and decode them with any function below,
// then add the new sky seen through the probe's visibility:
//   e = bakerRelitIrradiance(bakerSampleIrradianceX(rest, uvw, n), bakerSampleVisibilityX(vis, uvw, n), sky, n).
// sky[i] is the RGB of the sky radiance's SH coefficient i (index l·l + l + m, world axes),
// L_lm = ∫ L(ω) Y_lm(ω) dω: nine numbers per channel an engine computes from its sky each frame.

// The sky's irradiance on an unoccluded surface of unit normal n, Σ A_l L_lm Y_lm(n), A = π, 2π/3, π/4.
vec3 bakerSkyIrradiance(vec3 sky[9], vec3 n) {
  float y[9];
  bakerShL2Basis(n, y);
  const float band[9] = float[9](3.141592654, 2.094395102, 2.094395102, 2.094395102, 0.785398163, 0.785398163,
                                 0.785398163, 0.785398163, 0.785398163);
  vec3 e = vec3(0.0);
  for (int i = 0; i < 9; ++i) e += band[i] * y[i] * sky[i];
  return e;
}

vec3 bakerRelitIrradiance(vec3 rest, float visibility, vec3 sky[9], vec3 n) {
  return rest + visibility * bakerSkyIrradiance(sky, n);
}

// R, G and B of function i of a basis with `count` functions per channel.
#define BAKER_RGB(t, count, i) vec3(t[(i) >> 2][(i) & 3], t[((count) + (i)) >> 2][((count) + (i)) & 3], \
                                    t[(2 * (count) + (i)) >> 2][(2 * (count) + (i)) & 3])

vec3 bakerIrradianceShL1(vec4 t[3], vec3 n) {
  vec4 y = bakerShL1Basis(n);
  return vec3(dot(t[0], y), dot(t[1], y), dot(t[2], y));
}

vec3 bakerIrradianceShL2(vec4 t[7], vec3 n) {
  float y[9];
  bakerShL2Basis(n, y);
  vec3 e = vec3(0.0);
  for (int i = 0; i < 9; ++i) e += y[i] * BAKER_RGB(t, 9, i);
  return e;
}

float bakerVisibilityShL1(vec4 t[1], vec3 n) { return dot(t[0], bakerShL1Basis(n)); }

float bakerVisibilityShL2(vec4 t[3], vec3 n) {
  float y[9];
  bakerShL2Basis(n, y);
  float v = 0.0;
  for (int i = 0; i < 9; ++i) v += y[i] * t[i >> 2][i & 3];
  return v;
}

// ---- Ambient cube: max(0, ±axis·n)² lobes in the order +x, −x, +y, −y, +z, −z.

vec3 bakerIrradianceAmbientCube(vec4 t[5], vec3 n) {
  vec3 e = vec3(0.0);
  for (int axis = 0; axis < 3; ++axis) {
    int lobe = 2 * axis + (n[axis] < 0.0 ? 1 : 0);
    e += n[axis] * n[axis] * BAKER_RGB(t, 6, lobe);
  }
  return e;
}

float bakerVisibilityAmbientCube(vec4 t[2], vec3 n) {
  float v = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    int lobe = 2 * axis + (n[axis] < 0.0 ? 1 : 0);
    v += n[axis] * n[axis] * t[lobe >> 2][lobe & 3];
  }
  return v;
}

// ---- Ambient Dice: the icosahedron in the coefficients' vertex order. With Φ = (√5 − 1)/2:
// 0–3 (±1, ±Φ, 0), 4–7 (0, ±1, ±Φ), 8–11 (±Φ, 0, ±1); bit 0 of the index is the sign of the
// first non-zero coordinate, bit 1 that of the second (set: negative).

const float BAKER_PHI = 0.6180339887498949;
const vec3 BAKER_ICOSAHEDRON[12] = vec3[12](
    normalize(vec3(1.0, BAKER_PHI, 0.0)), normalize(vec3(-1.0, BAKER_PHI, 0.0)),
    normalize(vec3(1.0, -BAKER_PHI, 0.0)), normalize(vec3(-1.0, -BAKER_PHI, 0.0)),
    normalize(vec3(0.0, 1.0, BAKER_PHI)), normalize(vec3(0.0, -1.0, BAKER_PHI)),
    normalize(vec3(0.0, 1.0, -BAKER_PHI)), normalize(vec3(0.0, -1.0, -BAKER_PHI)),
    normalize(vec3(BAKER_PHI, 0.0, 1.0)), normalize(vec3(-BAKER_PHI, 0.0, 1.0)),
    normalize(vec3(BAKER_PHI, 0.0, -1.0)), normalize(vec3(-BAKER_PHI, 0.0, -1.0)));

// The tangent of vertex i's derivative frame: the axis in which the vertex has a zero
// coordinate (z, x, y for the three groups); the bitangent is cross(vertex, tangent).
vec3 bakerIcosahedronTangent(int i) {
  int group = i >> 2;
  return vec3(group == 1, group == 2, group == 0);
}

// The vertices of the triangle containing unit d. The octant's signs pick one vertex of each
// group; planes through the origin and that triangle's edges tell whether d lies beyond one,
// in the neighbouring triangle that swaps the far vertex.
ivec3 bakerIcosahedronTriangle(vec3 d) {
  ivec3 s = ivec3(lessThan(d, vec3(0.0)));
  vec3 a = abs(d);
  const float phi = BAKER_PHI, phi2 = 1.0 - BAKER_PHI;
  int va = s.x + 2 * s.y, vb = 4 + s.y + 2 * s.z, vc = 8 + s.x + 2 * s.z;
  if (phi2 * a.x - phi * a.y + a.z <= 0.0)
    vc = vb ^ 2;
  else if (-phi * a.x + a.y + phi2 * a.z <= 0.0)
    vb = va ^ 2;
  else if (a.x + phi2 * a.y - phi * a.z <= 0.0)
    va = vc ^ 1;
  return ivec3(va, vb, vc);
}

// b = [v0 v1 v2]⁻¹ d; they sum to 1 only at the vertices (divide by the sum for flat ones).
vec3 bakerSphericalBarycentrics(ivec3 triangle, vec3 d) {
  vec3 v0 = BAKER_ICOSAHEDRON[triangle.x], v1 = BAKER_ICOSAHEDRON[triangle.y], v2 = BAKER_ICOSAHEDRON[triangle.z];
  vec3 r0 = cross(v1, v2), r1 = cross(v2, v0), r2 = cross(v0, v1);
  return vec3(dot(d, r0), dot(d, r1), dot(d, r2)) / dot(v0, r0);
}

// Linear interpolation of vertex values in flat barycentrics (ad-linear).
vec3 bakerIrradianceAdLinear(vec4 t[9], vec3 n) {
  ivec3 triangle = bakerIcosahedronTriangle(n);
  vec3 b = bakerSphericalBarycentrics(triangle, n);
  b /= b.x + b.y + b.z;
  return b.x * BAKER_RGB(t, 12, triangle.x) + b.y * BAKER_RGB(t, 12, triangle.y) + b.z * BAKER_RGB(t, 12, triangle.z);
}

float bakerVisibilityAdLinear(vec4 t[3], vec3 n) {
  ivec3 triangle = bakerIcosahedronTriangle(n);
  vec3 b = bakerSphericalBarycentrics(triangle, n);
  b /= b.x + b.y + b.z;
  float v = 0.0;
  for (int k = 0; k < 3; ++k) v += b[k] * t[triangle[k] >> 2][triangle[k] & 3];
  return v;
}

// Lobe weights cos2·c² + cos4·c⁴, c = max(0, vertex·n), for ad-cos2 and ad-srbf; normalised so
// the 12 lobes sum to 1 (ad-srbf is the paper's 0.7c² + 0.3c⁴ over 2·0.7 + 1.2·0.3).
const vec2 BAKER_AD_COS2_LOBE = vec2(0.5, 0.0);
const vec2 BAKER_AD_SRBF_LOBE = vec2(0.7, 0.3) / 1.76;

float bakerIcosahedronLobe(int i, vec3 n, vec2 lobe) {
  float c = max(dot(BAKER_ICOSAHEDRON[i], n), 0.0);
  return c * c * (lobe.x + lobe.y * c * c);
}

vec3 bakerIrradianceAdLobes(vec4 t[9], vec3 n, vec2 lobe) {
  vec3 e = vec3(0.0);
  for (int i = 0; i < 12; ++i) e += bakerIcosahedronLobe(i, n, lobe) * BAKER_RGB(t, 12, i);
  return e;
}

float bakerVisibilityAdLobes(vec4 t[3], vec3 n, vec2 lobe) {
  float v = 0.0;
  for (int i = 0; i < 12; ++i) v += bakerIcosahedronLobe(i, n, lobe) * t[i >> 2][i & 3];
  return v;
}

vec3 bakerIrradianceAdCos2(vec4 t[9], vec3 n) { return bakerIrradianceAdLobes(t, n, BAKER_AD_COS2_LOBE); }
vec3 bakerIrradianceAdSrbf(vec4 t[9], vec3 n) { return bakerIrradianceAdLobes(t, n, BAKER_AD_SRBF_LOBE); }
float bakerVisibilityAdCos2(vec4 t[3], vec3 n) { return bakerVisibilityAdLobes(t, n, BAKER_AD_COS2_LOBE); }
float bakerVisibilityAdSrbf(vec4 t[3], vec3 n) { return bakerVisibilityAdLobes(t, n, BAKER_AD_SRBF_LOBE); }

// The hybrid cubic Bézier patch in spherical barycentrics b (Ambient Dice §2.3.1), from the
// data of the triangle's corners: data[3k + j] is datum j (value, ∂t, ∂b) of corner k. Edge
// points c_km = f_k/√5 + (√5/2)(v_m·∇_k)/(3α), ∇_k = ∂t·t_k + ∂b·b_k, α = ½√((5 + √5)/2); the
// centre blends three points, each making the patch C1 across one edge.
float bakerBezierPatch(ivec3 triangle, vec3 b, float data[9]) {
  const float root5 = 2.2360679775;
  const float vertexFactor = 1.0 / root5;
  const vec3 interior = vec3((root5 - 5.0) / 40.0, (11.0 * root5 - 15.0) / 40.0, root5 / 10.0);
  const float edgeScale = root5 / (6.0 * 0.5 * sqrt((5.0 + root5) / 2.0));
  vec3 vertex[3], gradient[3];
  float corner[3], edge[9];  // edge[3k + m]: the control point next to corner k towards m
  for (int k = 0; k < 3; ++k) {
    vertex[k] = BAKER_ICOSAHEDRON[triangle[k]];
    vec3 tangent = bakerIcosahedronTangent(triangle[k]);
    corner[k] = data[3 * k];
    gradient[k] = data[3 * k + 1] * tangent + data[3 * k + 2] * cross(vertex[k], tangent);
  }
  for (int k = 0; k < 3; ++k)
    for (int m = 0; m < 3; ++m) edge[3 * k + m] = vertexFactor * corner[k] + edgeScale * dot(vertex[m], gradient[k]);

  float value = 0.0;
  for (int k = 0; k < 3; ++k) {
    value += b[k] * b[k] * b[k] * corner[k];
    for (int m = 0; m < 3; ++m)
      if (m != k) value += 3.0 * b[k] * b[k] * b[m] * edge[3 * k + m];
  }
  vec3 p = max(b, vec3(0.0));
  vec3 q = vec3(p.y * p.z, p.x * p.z, p.x * p.y);
  float qSum = q.x + q.y + q.z;
  if (qSum <= 0.0) return value;  // at a vertex, where the centre term vanishes
  vec3 w = q / qSum;
  float centre = 0.0;
  for (int j = 0; j < 3; ++j) {
    int k = (j + 1) % 3, m = (j + 2) % 3;
    centre += w[j] * (interior.x * (corner[k] + corner[m]) + interior.y * (edge[3 * k + m] + edge[3 * m + k]) +
                      interior.z * (edge[3 * k + j] + edge[3 * m + j]));
  }
  return value + 6.0 * b.x * b.y * b.z * centre;
}

// ad-ycocg: Y as the Bézier patch (36 numbers), Co and Cg linear in spherical barycentrics
// (12 each, at 36 and 48).
vec3 bakerIrradianceAdYCoCg(vec4 t[15], vec3 n) {
  ivec3 triangle = bakerIcosahedronTriangle(n);
  vec3 b = bakerSphericalBarycentrics(triangle, n);
  float data[9];
  float co = 0.0, cg = 0.0;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      int s = 3 * triangle[k] + j;
      data[3 * k + j] = t[s >> 2][s & 3];
    }
    int sco = 36 + triangle[k], scg = 48 + triangle[k];
    co += b[k] * t[sco >> 2][sco & 3];
    cg += b[k] * t[scg >> 2][scg & 3];
  }
  float y = bakerBezierPatch(triangle, b, data);
  return vec3(y + co - cg, y + cg, y - co - cg);
}

float bakerVisibilityAdYCoCg(vec4 t[9], vec3 n) {
  ivec3 triangle = bakerIcosahedronTriangle(n);
  float data[9];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) {
      int s = 3 * triangle[k] + j;
      data[3 * k + j] = t[s >> 2][s & 3];
    }
  return bakerBezierPatch(triangle, bakerSphericalBarycentrics(triangle, n), data);
}

// ---- Fetch and decode: one trilinear fetch per texture at uvw (bakerVolumeCoordinate).

#define BAKER_FETCH(textures, count, uvw, texels) \
  vec4 texels[count];                             \
  for (int k = 0; k < count; ++k) texels[k] = texture(textures[k], uvw)

vec3 bakerSampleIrradianceShL1(sampler3D textures[3], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 3, uvw, t);
  return bakerIrradianceShL1(t, n);
}
vec3 bakerSampleIrradianceShL2(sampler3D textures[7], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 7, uvw, t);
  return bakerIrradianceShL2(t, n);
}
vec3 bakerSampleIrradianceAmbientCube(sampler3D textures[5], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 5, uvw, t);
  return bakerIrradianceAmbientCube(t, n);
}
vec3 bakerSampleIrradianceAdLinear(sampler3D textures[9], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 9, uvw, t);
  return bakerIrradianceAdLinear(t, n);
}
vec3 bakerSampleIrradianceAdCos2(sampler3D textures[9], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 9, uvw, t);
  return bakerIrradianceAdCos2(t, n);
}
vec3 bakerSampleIrradianceAdSrbf(sampler3D textures[9], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 9, uvw, t);
  return bakerIrradianceAdSrbf(t, n);
}
vec3 bakerSampleIrradianceAdYCoCg(sampler3D textures[15], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 15, uvw, t);
  return bakerIrradianceAdYCoCg(t, n);
}

float bakerSampleVisibilityShL1(sampler3D textures[1], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 1, uvw, t);
  return bakerVisibilityShL1(t, n);
}
float bakerSampleVisibilityShL2(sampler3D textures[3], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 3, uvw, t);
  return bakerVisibilityShL2(t, n);
}
float bakerSampleVisibilityAmbientCube(sampler3D textures[2], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 2, uvw, t);
  return bakerVisibilityAmbientCube(t, n);
}
float bakerSampleVisibilityAdLinear(sampler3D textures[3], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 3, uvw, t);
  return bakerVisibilityAdLinear(t, n);
}
float bakerSampleVisibilityAdCos2(sampler3D textures[3], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 3, uvw, t);
  return bakerVisibilityAdCos2(t, n);
}
float bakerSampleVisibilityAdSrbf(sampler3D textures[3], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 3, uvw, t);
  return bakerVisibilityAdSrbf(t, n);
}
float bakerSampleVisibilityAdYCoCg(sampler3D textures[9], vec3 uvw, vec3 n) {
  BAKER_FETCH(textures, 9, uvw, t);
  return bakerVisibilityAdYCoCg(t, n);
}

// ---- Radiance volumes (--signal radiance: "signal" is "radiance" in baker.reconstruction). The
// textures are packed as above but hold the incoming radiance L(ω) in the same functions, so
// bakerIrradianceX(t, d) above, read at a direction d, is the radiance arriving from d. Irradiance
// is each function's diffuse response K_i(n) = ∫ f_i(ω) max(0, n·ω) dω: SH bands scaled by the
// clamped cosine's A_l = π, 2π/3, π/4; a lobe max(0, a·ω)² gives π(1 + x)²/8 and max(0, a·ω)⁴
// π(1/16 + x/6 + x²/8 − x⁴/48), x = a·n (the "diffuse_response" series of the file, summed).
// ad-hemi9 (radiance only) is read here too: 27 numbers in 7 textures, visibility in 3. sg-N and
// the piecewise Ambient Dice variants have no radiance functions here (the C++ header decodes sg-N).

const float BAKER_PI = 3.14159265358979;

vec3 bakerIrradianceFromRadianceShL1(vec4 t[3], vec3 n) {
  vec4 y = bakerShL1Basis(n) * vec4(BAKER_PI, vec3(2.0 * BAKER_PI / 3.0));
  return vec3(dot(t[0], y), dot(t[1], y), dot(t[2], y));
}

vec3 bakerIrradianceFromRadianceShL2(vec4 t[7], vec3 n) {
  float y[9];
  bakerShL2Basis(n, y);
  vec3 e = vec3(0.0);
  for (int i = 0; i < 9; ++i) e += y[i] * (i == 0 ? BAKER_PI : i < 4 ? 2.0 * BAKER_PI / 3.0 : BAKER_PI / 4.0) * BAKER_RGB(t, 9, i);
  return e;
}

// The response of the lobe cos2·max(0, a·ω)² + cos4·max(0, a·ω)⁴ at x = a·n.
float bakerLobeResponse(float x, vec2 lobe) {
  float x2 = x * x;
  return BAKER_PI * (lobe.x * (1.0 + x) * (1.0 + x) / 8.0 + lobe.y * (1.0 / 16.0 + x / 6.0 + x2 / 8.0 - x2 * x2 / 48.0));
}

// Every lobe responds where it faces away too (only the one at a·n = −1 gives 0), so all 6 count.
vec3 bakerIrradianceFromRadianceAmbientCube(vec4 t[5], vec3 n) {
  vec3 e = vec3(0.0);
  for (int lobe = 0; lobe < 6; ++lobe) {
    float x = (lobe % 2 == 0 ? 1.0 : -1.0) * n[lobe / 2];
    e += bakerLobeResponse(x, vec2(1.0, 0.0)) * BAKER_RGB(t, 6, lobe);
  }
  return e;
}

vec3 bakerIrradianceFromRadianceAdLobes(vec4 t[9], vec3 n, vec2 lobe) {
  vec3 e = vec3(0.0);
  for (int i = 0; i < 12; ++i) e += bakerLobeResponse(dot(BAKER_ICOSAHEDRON[i], n), lobe) * BAKER_RGB(t, 12, i);
  return e;
}

// ad-hemi9's lobe axes about +Y (the default --hemisphere-axis): the icosahedron turned so that its
// face centre (1, 1, 1)/√3 points along +Y, without the three vertices below y = −1/2. For a
// volume baked about another axis, put the 9 "axes" of its function set in a uniform vec3[9] and
// #define BAKER_AD_HEMI9_AXES as that uniform's name before including this file.
const vec3 BAKER_AD_HEMI9_AXES_UP[9] = vec3[9](
    vec3(0.367356142, 0.794654472, -0.483294667), vec3(-0.974418140, -0.187592474, -0.123767332),
    vec3(0.974418140, 0.187592474, 0.123767332), vec3(-0.602223530, 0.794654472, -0.076492418),
    vec3(0.380023417, -0.187592474, 0.905754529), vec3(-0.380023417, 0.187592474, -0.905754529),
    vec3(0.234867388, 0.794654472, 0.559787084), vec3(-0.594394723, 0.187592474, 0.781987197),
    vec3(0.594394723, -0.187592474, -0.781987197));
#ifndef BAKER_AD_HEMI9_AXES
#define BAKER_AD_HEMI9_AXES BAKER_AD_HEMI9_AXES_UP
#endif

// The radiance arriving from d.
vec3 bakerRadianceAdHemi9(vec4 t[7], vec3 d) {
  vec3 l = vec3(0.0);
  for (int i = 0; i < 9; ++i) {
    float c = max(dot(BAKER_AD_HEMI9_AXES[i], d), 0.0);
    l += c * c * (BAKER_AD_SRBF_LOBE.x + BAKER_AD_SRBF_LOBE.y * c * c) * BAKER_RGB(t, 9, i);
  }
  return l;
}

vec3 bakerIrradianceFromRadianceAdHemi9(vec4 t[7], vec3 n) {
  vec3 e = vec3(0.0);
  for (int i = 0; i < 9; ++i) e += bakerLobeResponse(dot(BAKER_AD_HEMI9_AXES[i], n), BAKER_AD_SRBF_LOBE) * BAKER_RGB(t, 9, i);
  return e;
}

float bakerVisibilityFromRadianceAdHemi9(vec4 t[3], vec3 n) {
  float v = 0.0;
  for (int i = 0; i < 9; ++i) v += bakerLobeResponse(dot(BAKER_AD_HEMI9_AXES[i], n), BAKER_AD_SRBF_LOBE) * t[i >> 2][i & 3];
  return v / BAKER_PI;
}

vec3 bakerIrradianceFromRadianceAdCos2(vec4 t[9], vec3 n) { return bakerIrradianceFromRadianceAdLobes(t, n, BAKER_AD_COS2_LOBE); }
vec3 bakerIrradianceFromRadianceAdSrbf(vec4 t[9], vec3 n) { return bakerIrradianceFromRadianceAdLobes(t, n, BAKER_AD_SRBF_LOBE); }

// Sky visibility (1/π)∫V(ω) max(0, n·ω) dω from V(ω) stored in channel 0's functions.
float bakerVisibilityFromRadianceShL1(vec4 t[1], vec3 n) {
  return dot(t[0], bakerShL1Basis(n) * vec4(1.0, vec3(2.0 / 3.0)));
}
float bakerVisibilityFromRadianceShL2(vec4 t[3], vec3 n) {
  float y[9];
  bakerShL2Basis(n, y);
  float v = 0.0;
  for (int i = 0; i < 9; ++i) v += y[i] * (i == 0 ? 1.0 : i < 4 ? 2.0 / 3.0 : 0.25) * t[i >> 2][i & 3];
  return v;
}
float bakerVisibilityFromRadianceAmbientCube(vec4 t[2], vec3 n) {
  float v = 0.0;
  for (int lobe = 0; lobe < 6; ++lobe)
    v += bakerLobeResponse((lobe % 2 == 0 ? 1.0 : -1.0) * n[lobe / 2], vec2(1.0, 0.0)) * t[lobe >> 2][lobe & 3];
  return v / BAKER_PI;
}
float bakerVisibilityFromRadianceAdLobes(vec4 t[3], vec3 n, vec2 lobe) {
  float v = 0.0;
  for (int i = 0; i < 12; ++i) v += bakerLobeResponse(dot(BAKER_ICOSAHEDRON[i], n), lobe) * t[i >> 2][i & 3];
  return v / BAKER_PI;
}
float bakerVisibilityFromRadianceAdCos2(vec4 t[3], vec3 n) { return bakerVisibilityFromRadianceAdLobes(t, n, BAKER_AD_COS2_LOBE); }
float bakerVisibilityFromRadianceAdSrbf(vec4 t[3], vec3 n) { return bakerVisibilityFromRadianceAdLobes(t, n, BAKER_AD_SRBF_LOBE); }

// Glossy specular (docs/DECODERS.md "Glossy specular"): S = (1 − w)·L(r) + w·E(n)/π for a GGX
// lobe with F0 = 1, α = roughness². `blend` is "baker.specular" as a 16 × 16 two-channel float
// texture (R = diffuse_weight, G = albedo; row j = roughness j/15, column k = n·v k/15), read here
// with texelFetch and blended exactly as the library does, so any filter mode works. The result
// is (S, albedo): the reflected radiance is albedo·F·S.
struct BakerSpecularRead {
  vec3 reflection;  // r = 2(n·v)n − v for n·v clamped to [1e-4, 1] in the plane of n and v
  vec2 blend;       // (w, albedo)
};

BakerSpecularRead bakerSpecularRead(vec3 n, vec3 v, float roughness, sampler2D blend) {
  float nv = dot(n, v), cosView = clamp(nv, 1e-4, 1.0);
  vec3 along = v - nv * n;
  // v along n: any tangent (as the library's, from Eigen's unitOrthogonal).
  if (length(along) < 1e-6) along = abs(n.x) > 1e-6 || abs(n.y) > 1e-6 ? vec3(-n.y, n.x, 0.0) : vec3(0.0, -n.z, n.y);
  vec3 view = cosView * n + sqrt(1.0 - cosView * cosView) * normalize(along);
  vec2 grid = vec2(clamp(roughness, 0.0, 1.0), cosView) * 15.0;
  ivec2 low = min(ivec2(grid), ivec2(14));
  vec2 f = grid - vec2(low);
  vec2 w00 = texelFetch(blend, ivec2(low.y, low.x), 0).rg, w01 = texelFetch(blend, ivec2(low.y + 1, low.x), 0).rg;
  vec2 w10 = texelFetch(blend, ivec2(low.y, low.x + 1), 0).rg, w11 = texelFetch(blend, ivec2(low.y + 1, low.x + 1), 0).rg;
  return BakerSpecularRead(2.0 * cosView * n - view, mix(mix(w00, w01, f.y), mix(w10, w11, f.y), f.x));
}

// vec4 bakerSpecular<B>(vec4 t[N], vec3 n, vec3 v, float roughness, sampler2D blend) for B = ShL1,
// ShL2, AmbientCube, AdCos2, AdSrbf, AdHemi9: the same blend of each basis's radiance at the
// mirror direction and its irradiance.
#define BAKER_SPECULAR(Name, count, radianceFrom)                                                        \
  vec4 bakerSpecular##Name(vec4 t[count], vec3 n, vec3 v, float roughness, sampler2D blend) {             \
    BakerSpecularRead r = bakerSpecularRead(n, v, roughness, blend);                                      \
    return vec4(mix(radianceFrom(t, r.reflection), bakerIrradianceFromRadiance##Name(t, n) / BAKER_PI, r.blend.x), \
                r.blend.y);                                                                               \
  }
BAKER_SPECULAR(ShL1, 3, bakerIrradianceShL1)
BAKER_SPECULAR(ShL2, 7, bakerIrradianceShL2)
BAKER_SPECULAR(AmbientCube, 5, bakerIrradianceAmbientCube)
BAKER_SPECULAR(AdCos2, 9, bakerIrradianceAdCos2)
BAKER_SPECULAR(AdSrbf, 9, bakerIrradianceAdSrbf)
BAKER_SPECULAR(AdHemi9, 7, bakerRadianceAdHemi9)

// ---- Leak-aware weights (docs/LEAKS.md). A volume with "baker.distance_map" holds per probe an
// N × N octahedral map of the mean and mean squared distance to the first surface, in units of
// the map's cap. Pack each probe's map as an N × N tile of a two-channel texture (R: value 2t,
// G: value 2t + 1 of texel t = i + N·j at tile texel (i, j): a .vdb's atlas grid distance_map
// already holds probe (x, y, z)'s tile at (x·N, y·N) of slice z, R and G as here); `tile` is its
// first texel. Multiply each corner's trilinear weight by bakerLeakWeight and divide by the sum of
// the products.
vec2 bakerOctahedralEncode(vec3 d) {
  vec2 p = d.xz / (abs(d.x) + abs(d.y) + abs(d.z));
  if (d.y < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x < 0.0 ? -1.0 : 1.0, p.y < 0.0 ? -1.0 : 1.0);
  return 0.5 * (p + 1.0);
}

// `probe`: where the probe was baked (grid position plus probe_offset); `point` on a surface of
// unit `normal`.
float bakerLeakWeight(sampler2D moments, ivec2 tile, int size, float cap, vec3 probe, vec3 point, vec3 normal,
                      float spacing) {
  vec3 fromProbe = point + 0.25 * spacing * normal - probe;
  float r = length(fromProbe);
  if (!(r > 0.0) || isinf(r)) return 1.0;
  vec3 direction = fromProbe / r;
  vec2 x = bakerOctahedralEncode(direction) * float(size) - 0.5;
  ivec2 low = clamp(ivec2(floor(x)), ivec2(0), ivec2(size - 2));
  vec2 f = clamp(x - vec2(low), 0.0, 1.0);
  vec2 m00 = texelFetch(moments, tile + low, 0).rg, m10 = texelFetch(moments, tile + low + ivec2(1, 0), 0).rg;
  vec2 m01 = texelFetch(moments, tile + low + ivec2(0, 1), 0).rg, m11 = texelFetch(moments, tile + low + ivec2(1, 1), 0).rg;
  bool open = (m00.x >= 1.0 || (1.0 - f.x) * (1.0 - f.y) == 0.0) && (m10.x >= 1.0 || f.x * (1.0 - f.y) == 0.0) &&
              (m01.x >= 1.0 || (1.0 - f.x) * f.y == 0.0) && (m11.x >= 1.0 || f.x * f.y == 0.0);
  if (open) return 1.0;
  vec2 m = mix(mix(m00, m10, f.x), mix(m01, m11, f.x), f.y) * vec2(cap, cap * cap);
  float facing = 0.5 * (1.0 - dot(direction, normal));
  float weight = (facing * facing + 0.2) / 1.2;
  if (r > m.x) {
    float variance = abs(m.y - m.x * m.x), beyond = r - m.x;
    float chebyshev = variance / (variance + beyond * beyond);
    weight *= chebyshev * chebyshev * chebyshev;
  }
  // The paper's floor and crush threshold, divided by 1.2 with its back-face weight.
  const float crush = 0.2 / 1.2;
  weight = max(weight, 1e-6 / 1.2);
  if (weight < crush) weight *= weight * weight / (crush * crush);
  return weight;
}

// ---- Adaptive volumes (docs/DECODERS.md "Adaptive volumes on the GPU"); include
// baker_adaptive.glsl first. The pool's textures are packed as above, per probe of a pool slot:
// an atlas of slots, slot s at texel 8·(s mod S, (s / S) mod S, s / S²) + the probe's place in
// its brick, S = slotsAcross (the EXR atlas's rule). Filter GL_NEAREST: bricks that are
// neighbours in the volume are not neighbours in the atlas, so the eight corners are fetched and
// blended here. For example, ad-ycocg:
//   BakerCorners corners = bakerAdaptiveCorners(worldPosition, indirection, levelCount, levelOrigin,
//                                                levelSpacing, levelDims, levelBrickZ);
//   BAKER_ADAPTIVE_FETCH(pool, 15, corners, slotsAcross, t);
//   vec3 e = bakerIrradianceAdYCoCg(t, n);

ivec3 bakerPoolTexel(int slot, ivec3 local, int slotsAcross) {
  ivec3 s = ivec3(slot % slotsAcross, (slot / slotsAcross) % slotsAcross, slot / (slotsAcross * slotsAcross));
  return 8 * s + local;
}

#define BAKER_ADAPTIVE_FETCH(textures, count, corners, slotsAcross, texels)                             \
  vec4 texels[count];                                                                                   \
  for (int k = 0; k < count; ++k) {                                                                     \
    texels[k] = vec4(0.0);                                                                              \
    for (int c = 0; c < 8; ++c)                                                                         \
      texels[k] += corners.weight[c] *                                                                  \
                   texelFetch(textures[k], bakerPoolTexel(corners.slot[c], corners.local[c], slotsAcross), 0); \
  }
