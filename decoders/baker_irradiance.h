// baker_irradiance.h — reference decoder for baker irradiance volumes. Self-contained (C++11,
// standard library only): copy it into an engine or importer as it is.
//
// A volume stores, per probe, the coefficients of the irradiance E(n) = ∫ L(ω) max(0, n·ω) dω
// in one basis ("baker.basis" in the file), channel after channel of the basis's colour space
// (RGB, or YCoCg for ad-ycocg): channel c holds coefficientCount(c) numbers at
// coefficientOffset(c). BasisDecoder turns one probe's numbers into RGB irradiance at a unit
// normal n; probeNeighbourhood and blendProbes interpolate the probes around a point first.
//
//   baker_decode::BasisDecoder decoder("ad-ycocg");   // sg-N: pass the "sharpness" of baker.reconstruction
//   baker_decode::Rgb e = decoder.irradiance(probeCoefficients, baker_decode::Vec3{0, 1, 0});
//
// A volume baked with --signal radiance ("signal": "radiance" in "baker.reconstruction") holds
// the incoming radiance L(ω) in the same functions instead: radiance() evaluates it,
// irradianceFromRadiance() gives E(n) from each function's diffuse response, and specular() a
// GGX lobe's mean radiance from the file's "baker.specular" table.
//
// The formulas are in docs/DECODERS.md; the same constants are in the file's
// "baker.reconstruction" metadata.
#ifndef BAKER_IRRADIANCE_H
#define BAKER_IRRADIANCE_H

#include <cmath>
#include <cstring>

namespace baker_decode {

struct Vec3 {
  double x, y, z;
};

struct Rgb {
  double r, g, b;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return Vec3{a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator*(double s, const Vec3& v) { return Vec3{s * v.x, s * v.y, s * v.z}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 normalize(const Vec3& v) { return (1.0 / std::sqrt(dot(v, v))) * v; }

const double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// The icosahedron of Ambient Dice (Iwanicki & Sloan 2017, §2.2), in the order of the
// coefficients. With Φ = (√5 − 1)/2, before normalising: vertices 0–3 are (±1, ±Φ, 0), 4–7
// (0, ±1, ±Φ), 8–11 (±Φ, 0, ±1); within a group bit 0 of the index is the sign of the first
// non-zero coordinate, bit 1 that of the second (1: negative). Vertex i ^ 3 is i's antipode.

const double kIcosahedronPhi = 0.61803398874989484820;

inline Vec3 icosahedronVertex(int i) {
  const double first = (i & 1) ? -1.0 : 1.0, second = (i & 2) ? -1.0 : 1.0;
  const double phi = kIcosahedronPhi;
  switch (i / 4) {
    case 0: return normalize(Vec3{first, second * phi, 0.0});
    case 1: return normalize(Vec3{0.0, first, second * phi});
    default: return normalize(Vec3{first * phi, 0.0, second});
  }
}

// The frame the Bézier variants' derivative data refer to: t is the coordinate axis in which
// the vertex has a zero coordinate, b = v̂ × t.
inline Vec3 icosahedronTangent(int i) {
  switch (i / 4) {
    case 0: return Vec3{0.0, 0.0, 1.0};
    case 1: return Vec3{1.0, 0.0, 0.0};
    default: return Vec3{0.0, 1.0, 0.0};
  }
}
inline Vec3 icosahedronBitangent(int i) { return cross(icosahedronVertex(i), icosahedronTangent(i)); }

// The icosahedron triangle that contains a direction, and the direction's barycentrics in it.
struct IcosahedronTriangle {
  int vertex[3];
  // b = [v̂0 v̂1 v̂2]⁻¹ d: spherical barycentrics (they sum to 1 only at the vertices).
  double spherical[3];
  // b / (b0 + b1 + b2): where d meets the flat face.
  double flat[3];
};

// Mirror d into the positive octant: the triangle there has one vertex of each group, and the
// rest of the octant is covered by the three triangles beyond its edges, each of which swaps
// one of those vertices for another. A plane through the origin and each edge decides.
inline IcosahedronTriangle locateOnIcosahedron(const Vec3& d) {
  const int sx = d.x < 0.0, sy = d.y < 0.0, sz = d.z < 0.0;
  const double ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  const double phi = kIcosahedronPhi, phi2 = 1.0 - kIcosahedronPhi;  // Φ² = 1 − Φ
  int a = sx + 2 * sy, b = 4 + sy + 2 * sz, c = 8 + sx + 2 * sz;
  // Planes through the edges BC, CA and AB of the octant's triangle (normals B×C, C×A, A×B for
  // A = (1, Φ, 0), B = (0, 1, Φ), C = (Φ, 0, 1)); beyond one of them the far vertex is replaced.
  // Near a vertex two tests may fail; either neighbouring triangle then contains d.
  if (phi2 * ax - phi * ay + az <= 0.0)
    c = b ^ 2;  // beyond AB: (0, 1, −Φ)
  else if (-phi * ax + ay + phi2 * az <= 0.0)
    b = a ^ 2;  // beyond CA: (1, −Φ, 0)
  else if (ax + phi2 * ay - phi * az <= 0.0)
    a = c ^ 1;  // beyond BC: (−Φ, 0, 1)

  IcosahedronTriangle t;
  t.vertex[0] = a, t.vertex[1] = b, t.vertex[2] = c;
  const Vec3 v0 = icosahedronVertex(a), v1 = icosahedronVertex(b), v2 = icosahedronVertex(c);
  const Vec3 r0 = cross(v1, v2), r1 = cross(v2, v0), r2 = cross(v0, v1);  // rows of the adjugate
  const double determinant = dot(v0, r0);
  t.spherical[0] = dot(d, r0) / determinant;
  t.spherical[1] = dot(d, r1) / determinant;
  t.spherical[2] = dot(d, r2) / determinant;
  const double sum = t.spherical[0] + t.spherical[1] + t.spherical[2];
  for (int k = 0; k < 3; ++k) t.flat[k] = t.spherical[k] / sum;
  return t;
}

// Lobe i of the N spherical Gaussians sits on the spherical Fibonacci point i of N.
inline Vec3 sphericalFibonacciAxis(int i, int n) {
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
  const double phi = kPi * (3.0 - std::sqrt(5.0)) * i;
  return Vec3{r * std::cos(phi), r * std::sin(phi), z};
}

// ---------------------------------------------------------------------------------------------
// Function sets: what one colour channel's coefficients are coefficients of.

enum class FunctionSetKind {
  SphericalHarmonics,  // (order+1)² real SH
  IcosahedronLinear,   // 12 vertex values, linear across each triangle
  IcosahedronLobes,    // 12 clamped-cosine lobes on the vertices
  IcosahedronBezier,   // 36: per vertex value, ∂t, ∂b; a cubic Bézier patch per triangle
  CubeLobes,           // 6 cos² lobes on ±x, ±y, ±z
  SphericalGaussians,  // N lobes exp(λ(μ·n − 1))
  HemisphereLobes,     // ad-hemi9: 9 lobes cos2·c² + cos4·c⁴, c = max(0, axis·n), on listed axes
};

enum class Barycentrics { Spherical, Flat };

const int kMaxShOrder = 64;
const int kMaxLobes = 64;
const int kMaxResponseTerms = 224;  // the most a file's series holds (basis/LegendreResponse.h)

struct FunctionSet {
  FunctionSetKind kind = FunctionSetKind::SphericalHarmonics;
  int shOrder = 0;
  Barycentrics barycentrics = Barycentrics::Spherical;  // linear and Bézier
  double cos2 = 0.0, cos4 = 0.0;                        // lobes: cos2·c² + cos4·c⁴, c = max(0, v̂·n)
  int lobeCount = 0;                                    // spherical Gaussians, hemisphere lobes
  double sharpness = 0.0;
  double axes[3 * kMaxLobes] = {};
  // Radiance: the lobes' diffuse response h(x) = Σ_l response[l] P_l(x), x = axis·n, for the
  // three radial kinds; 0 terms when unknown (spherical Gaussians until setDiffuseResponse).
  int responseTerms = 0;
  double response[kMaxResponseTerms] = {};

  int count() const {
    switch (kind) {
      case FunctionSetKind::SphericalHarmonics: return (shOrder + 1) * (shOrder + 1);
      case FunctionSetKind::IcosahedronLinear:
      case FunctionSetKind::IcosahedronLobes: return 12;
      case FunctionSetKind::IcosahedronBezier: return 36;
      case FunctionSetKind::CubeLobes: return 6;
      case FunctionSetKind::SphericalGaussians:
      case FunctionSetKind::HemisphereLobes: return lobeCount;
    }
    return 0;
  }
};

namespace detail {

// Real SH without the Condon–Shortley phase, polar axis z. With Q(l,m) = K(l,m)·P(l,m)(z)/sin^m θ
// (K the orthonormalising factor) the standard recurrences of the normalised Legendre functions
//   Q(m,m) = √((2m+1)/(2m))·Q(m−1,m−1),  Q(l,m) = A·(z·Q(l−1,m) − B·Q(l−2,m)),
//   A = √((4l² − 1)/(l² − m²)),  B = √(((l−1)² − m²)/(4(l−1)² − 1)),
// stay in range at any order, and sin^m θ·(cos mφ, sin mφ) is (x + iy)^m, so no angles appear.
// bandScale: null, or a factor per band l (the clamped cosine's, for irradiance from radiance).
inline void accumulateSphericalHarmonics(int order, const float* coefficients, int arrays, const Vec3& d, double* sums,
                                         const double* bandScale = nullptr) {
  const int count = (order + 1) * (order + 1);
  double re = 1.0, im = 0.0;                      // (x + iy)^m
  double diagonal = std::sqrt(1.0 / (4.0 * kPi));  // Q(m,m)
  for (int m = 0; m <= order; ++m) {
    if (m > 0) {
      const double nextRe = re * d.x - im * d.y;
      im = re * d.y + im * d.x;
      re = nextRe;
      diagonal *= std::sqrt((2.0 * m + 1.0) / (2.0 * m));
    }
    double previous = 0.0, current = diagonal;
    for (int l = m; l <= order; ++l) {
      if (l > m) {
        const double a = std::sqrt((4.0 * l * l - 1.0) / (double(l) * l - double(m) * m));
        const double b = std::sqrt(((l - 1.0) * (l - 1.0) - double(m) * m) / (4.0 * (l - 1.0) * (l - 1.0) - 1.0));
        const double next = a * (d.z * current - b * previous);
        previous = current;
        current = next;
      }
      const int centre = l * l + l;
      const double scaled = bandScale ? bandScale[l] * current : current;
      for (int k = 0; k < arrays; ++k) {
        const float* c = coefficients + k * count;
        if (m == 0)
          sums[k] += scaled * c[centre];
        else
          sums[k] += std::sqrt(2.0) * scaled * (re * c[centre + m] + im * c[centre - m]);
      }
    }
  }
}

// The cubic Bézier patch of one triangle (Ambient Dice §2.3.1). Control points: c_k = f_k at
// the corners; c_km = vf·f_k + (e_km·∇_k)/(3α) next to corner k on the edge towards m, with ∇_k
// = ∂t·t_k + ∂b·b_k the stored gradient and e_km the unit tangent at v̂_k towards v̂_m, which for
// neighbours (v̂_k·v̂_m = 1/√5) makes e_km·∇_k = (√5/2)·v̂_m·∇_k; the centre blends three points,
// each of which makes the patch C1 across one edge.
inline double bezierPatch(const IcosahedronTriangle& t, Barycentrics kind, const float* data) {
  const double root5 = std::sqrt(5.0);
  const bool spherical = kind == Barycentrics::Spherical;
  const double vertexFactor = spherical ? 1.0 / root5 : 1.0;
  const double a0 = spherical ? (root5 - 5.0) / 40.0 : -0.25;
  const double a1 = spherical ? (11.0 * root5 - 15.0) / 40.0 : 0.25;
  const double a2 = spherical ? root5 / 10.0 : 0.5;
  const double alpha = 0.5 * std::sqrt((5.0 + root5) / 2.0);
  const double* b = spherical ? t.spherical : t.flat;

  double corner[3], edge[3][3];
  Vec3 gradient[3];
  for (int k = 0; k < 3; ++k) {
    const float* vertexData = data + 3 * t.vertex[k];
    corner[k] = vertexData[0];
    gradient[k] = vertexData[1] * icosahedronTangent(t.vertex[k]) + vertexData[2] * icosahedronBitangent(t.vertex[k]);
  }
  for (int k = 0; k < 3; ++k)
    for (int m = 0; m < 3; ++m)
      edge[k][m] = vertexFactor * corner[k] + (root5 / 2.0) * dot(icosahedronVertex(t.vertex[m]), gradient[k]) / (3.0 * alpha);

  double value = 0.0;
  for (int k = 0; k < 3; ++k) {
    value += b[k] * b[k] * b[k] * corner[k];
    for (int m = 0; m < 3; ++m)
      if (m != k) value += 3.0 * b[k] * b[k] * b[m] * edge[k][m];
  }
  // Blend weights w_j ∝ b_{j+1}·b_{j+2} (barycentrics a rounding error below 0 count as 0); at
  // a vertex, where all are 0, the centre term vanishes anyway.
  double p[3], w[3];
  for (int k = 0; k < 3; ++k) p[k] = std::fmax(0.0, b[k]);
  const double weightSum = p[1] * p[2] + p[0] * p[2] + p[0] * p[1];
  if (weightSum <= 0.0) return value;
  for (int j = 0; j < 3; ++j) w[j] = p[(j + 1) % 3] * p[(j + 2) % 3] / weightSum;
  double centre = 0.0;
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3, m = (j + 2) % 3;
    centre += w[j] * (a0 * (corner[k] + corner[m]) + a1 * (edge[k][m] + edge[m][k]) + a2 * (edge[k][j] + edge[m][j]));
  }
  return value + 6.0 * b[0] * b[1] * b[2] * centre;
}

// A_l = 2π ∫₀¹ t P_l(t) dt: how the clamped cosine scales band l (π, 2π/3, π/4, 0, −π/24, …).
inline double clampedCosineBand(int l) {
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  double ratio = 1.0;  // l!/(2^l ((l/2)!)²), as a product that stays in range
  for (int k = 1; k <= l / 2; ++k) ratio *= double(l / 2 + k) / (4.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * ratio;
}

// Σ_l k[l] P_l(x), l < terms, by the three-term recurrence.
inline double legendreSeries(const double* k, int terms, double x) {
  if (terms <= 0) return 0.0;
  double sum = k[0], previous = 1.0, current = x;
  for (int l = 1; l < terms; ++l) {
    if (l > 1) {
      const double next = ((2.0 * l - 1.0) * x * current - (l - 1.0) * previous) / l;
      previous = current;
      current = next;
    }
    sum += k[l] * current;
  }
  return sum;
}

inline Vec3 cubeAxis(int lobe) {
  const double sign = lobe % 2 == 0 ? 1.0 : -1.0;
  return Vec3{lobe / 2 == 0 ? sign : 0.0, lobe / 2 == 1 ? sign : 0.0, lobe / 2 == 2 ? sign : 0.0};
}

}  // namespace detail

// Σ_i coefficients[k·count + i]·f_i(d) for k < arrays, into sums[k]: `arrays` channels that
// share the function set, stored one after the other (R, G, B of an RGB basis).
inline void expand(const FunctionSet& set, const float* coefficients, int arrays, const Vec3& d, double* sums) {
  const int count = set.count();
  for (int k = 0; k < arrays; ++k) sums[k] = 0.0;
  switch (set.kind) {
    case FunctionSetKind::SphericalHarmonics:
      detail::accumulateSphericalHarmonics(set.shOrder, coefficients, arrays, d, sums);
      return;
    case FunctionSetKind::IcosahedronLinear: {
      const IcosahedronTriangle t = locateOnIcosahedron(d);
      const double* b = set.barycentrics == Barycentrics::Spherical ? t.spherical : t.flat;
      for (int k = 0; k < arrays; ++k)
        for (int corner = 0; corner < 3; ++corner) sums[k] += b[corner] * coefficients[k * count + t.vertex[corner]];
      return;
    }
    case FunctionSetKind::IcosahedronLobes:
      for (int i = 0; i < 12; ++i) {
        const double c = dot(icosahedronVertex(i), d);
        if (c <= 0.0) continue;
        const double lobe = c * c * (set.cos2 + set.cos4 * c * c);
        for (int k = 0; k < arrays; ++k) sums[k] += lobe * coefficients[k * count + i];
      }
      return;
    case FunctionSetKind::IcosahedronBezier: {
      const IcosahedronTriangle t = locateOnIcosahedron(d);
      for (int k = 0; k < arrays; ++k) sums[k] = detail::bezierPatch(t, set.barycentrics, coefficients + k * count);
      return;
    }
    case FunctionSetKind::CubeLobes: {
      // Of the ± lobes of an axis only the one on d's side is non-zero; both are d[axis]² there.
      const double axis[3] = {d.x, d.y, d.z};
      for (int a = 0; a < 3; ++a) {
        const int lobe = 2 * a + (axis[a] < 0.0 ? 1 : 0);
        for (int k = 0; k < arrays; ++k) sums[k] += axis[a] * axis[a] * coefficients[k * count + lobe];
      }
      return;
    }
    case FunctionSetKind::SphericalGaussians:
      for (int i = 0; i < set.lobeCount; ++i) {
        const Vec3 mu{set.axes[3 * i], set.axes[3 * i + 1], set.axes[3 * i + 2]};
        const double lobe = std::exp(set.sharpness * (dot(mu, d) - 1.0));
        for (int k = 0; k < arrays; ++k) sums[k] += lobe * coefficients[k * count + i];
      }
      return;
    case FunctionSetKind::HemisphereLobes:
      for (int i = 0; i < set.lobeCount; ++i) {
        const double c = dot(Vec3{set.axes[3 * i], set.axes[3 * i + 1], set.axes[3 * i + 2]}, d);
        if (c <= 0.0) continue;
        const double lobe = c * c * (set.cos2 + set.cos4 * c * c);
        for (int k = 0; k < arrays; ++k) sums[k] += lobe * coefficients[k * count + i];
      }
      return;
  }
}

// Σ_i coefficients[k·count + i]·K_i(n): the irradiance of radiance stored in `set`, where
// K_i(n) = ∫ f_i(ω) max(0, n·ω) dω. False when the set's response is not known here.
inline bool expandIrradianceFromRadiance(const FunctionSet& set, const float* coefficients, int arrays, const Vec3& n,
                                         double* sums) {
  const int count = set.count();
  for (int k = 0; k < arrays; ++k) sums[k] = 0.0;
  if (set.kind == FunctionSetKind::SphericalHarmonics) {
    double bands[kMaxShOrder + 1];
    for (int l = 0; l <= set.shOrder; ++l) bands[l] = detail::clampedCosineBand(l);
    detail::accumulateSphericalHarmonics(set.shOrder, coefficients, arrays, n, sums, bands);
    return true;
  }
  const bool radial = set.kind == FunctionSetKind::IcosahedronLobes || set.kind == FunctionSetKind::CubeLobes ||
                      set.kind == FunctionSetKind::SphericalGaussians || set.kind == FunctionSetKind::HemisphereLobes;
  if (!radial || set.responseTerms <= 0) return false;
  for (int i = 0; i < count; ++i) {
    Vec3 axis;
    if (set.kind == FunctionSetKind::IcosahedronLobes)
      axis = icosahedronVertex(i);
    else if (set.kind == FunctionSetKind::CubeLobes)
      axis = detail::cubeAxis(i);
    else
      axis = Vec3{set.axes[3 * i], set.axes[3 * i + 1], set.axes[3 * i + 2]};
    const double response = detail::legendreSeries(set.response, set.responseTerms, dot(axis, n));
    for (int k = 0; k < arrays; ++k) sums[k] += response * coefficients[k * count + i];
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Glossy specular from a radiance volume: "baker.specular" (docs/DECODERS.md, "Glossy specular").

// The file's diffuse_weight and albedo, [roughness node j][n·v node k], nodes j/15 and k/15.
struct SpecularTable {
  static const int kSteps = 16;
  double diffuseWeight[kSteps][kSteps];
  double albedo[kSteps][kSteps];
};

// Bilinear in (roughness, n·v), both clamped to [0, 1].
inline double specularTableLookup(const double (&table)[SpecularTable::kSteps][SpecularTable::kSteps], double roughness,
                                  double cosView) {
  const int last = SpecularTable::kSteps - 1;
  const double x = std::fmin(std::fmax(roughness, 0.0), 1.0) * last, y = std::fmin(std::fmax(cosView, 0.0), 1.0) * last;
  const int j = x < last - 1 ? int(x) : last - 1, k = y < last - 1 ? int(y) : last - 1;
  const double fx = x - j, fy = y - k;
  return (1.0 - fx) * ((1.0 - fy) * table[j][k] + fy * table[j][k + 1]) +
         fx * ((1.0 - fy) * table[j + 1][k] + fy * table[j + 1][k + 1]);
}

// The view the lobe is read at: n·v clamped to [1e-4, 1], in the plane of n and v (a view at or
// below the surface is taken just above it), and its mirror direction 2(n·v)n − v.
struct SpecularView {
  double cosView;
  Vec3 reflection;
};

inline SpecularView specularView(const Vec3& n, const Vec3& v) {
  Vec3 along = v + (-dot(n, v)) * n;
  if (std::sqrt(dot(along, along)) < 1e-12) {
    // v along n: any tangent (this one is Eigen's unitOrthogonal, as the library's).
    const double tiny = 1e-12 * std::fabs(n.z);
    along = std::fabs(n.x) > tiny || std::fabs(n.y) > tiny ? Vec3{-n.y, n.x, 0.0} : Vec3{0.0, -n.z, n.y};
  }
  const Vec3 tangent = normalize(along);
  SpecularView s;
  s.cosView = std::fmin(std::fmax(dot(n, v), 1e-4), 1.0);
  const Vec3 view = s.cosView * n + std::sqrt(1.0 - s.cosView * s.cosView) * tangent;
  s.reflection = (2.0 * s.cosView) * n + (-1.0) * view;
  return s;
}

struct Specular {
  Rgb value;             // S, the GGX-weighted mean radiance: reflected radiance = albedo·F·S
  double albedo;         // the lobe's directional albedo A (F0 = 1)
  double diffuseWeight;  // w of S = (1 − w)·L(r) + w·E(n)/π
};

inline Rgb ycocgToRgb(double y, double co, double cg) { return Rgb{y + co - cg, y + cg, y - co - cg}; }

// ---- Relighting at run time (docs/RELIGHTING.md) ----
// A sky is 27 numbers: its radiance's real SH to band 2, L_lm = ∫ L(ω) Y_lm(ω) dω in world axes
// (the SH above, index l² + l + m), R's nine, then G's, then B's. skyIrradiance is its irradiance
// on an unoccluded surface of unit normal n, E(n) = Σ A_l L_lm Y_lm(n), A = π, 2π/3, π/4.
inline Rgb skyIrradiance(const float* sky, const Vec3& n) {
  static const double bands[3] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0};
  double sums[3] = {0.0, 0.0, 0.0};
  detail::accumulateSphericalHarmonics(2, sky, 3, n, sums, bands);
  return Rgb{sums[0], sums[1], sums[2]};
}

// E(n) = E_rest(n) + V(n)·E_sky(n): the light that is not the sky's plus the new sky seen through
// the probe's cosine-weighted sky visibility.
inline Rgb relitIrradiance(const Rgb& rest, double visibility, const Rgb& sky) {
  return Rgb{rest.r + visibility * sky.r, rest.g + visibility * sky.g, rest.b + visibility * sky.b};
}

// ---------------------------------------------------------------------------------------------
// A basis by its name in "baker.basis".

class BasisDecoder {
 public:
  // sgSharpness: λ of an sg-N basis, the "sharpness" of its function set in
  // "baker.reconstruction" (it depends on N and on the bake's --sg-sharpness); ignored for
  // other bases. valid() is false for an unknown name or a missing λ.
  explicit BasisDecoder(const char* basisName, double sgSharpness = 0.0) { valid_ = parse(basisName, sgSharpness); }

  bool valid() const { return valid_; }
  bool isYCoCg() const { return ycocg_; }
  const FunctionSet& functions(int channel) const { return ycocg_ && channel > 0 ? chroma_ : primary_; }
  int coefficientCount(int channel) const { return functions(channel).count(); }
  int coefficientOffset(int channel) const {
    int offset = 0;
    for (int c = 0; c < channel; ++c) offset += coefficientCount(c);
    return offset;
  }
  int coefficientsPerProbe() const { return coefficientOffset(3); }

  // Lobe axes as listed in "baker.reconstruction" (3 numbers per lobe) for sg-N and ad-hemi9,
  // in place of the ones this decoder computes itself: sg-N's spherical Fibonacci points, and
  // ad-hemi9's about +Y, which a volume baked with another hemisphere_axis does not use.
  void setLobeAxes(const double* axes) {
    for (int i = 0; i < 3 * primary_.lobeCount; ++i) primary_.axes[i] = axes[i];
  }

  // RGB irradiance at unit normal n from one probe's coefficients (coefficientsPerProbe()).
  Rgb irradiance(const float* coefficients, const Vec3& n) const {
    double sums[3];
    if (!ycocg_) {
      expand(primary_, coefficients, 3, n, sums);
      return Rgb{sums[0], sums[1], sums[2]};
    }
    expand(primary_, coefficients, 1, n, sums);
    expand(chroma_, coefficients + primary_.count(), 2, n, sums + 1);
    return ycocgToRgb(sums[0], sums[1], sums[2]);
  }

  // Sky visibility (1/π)∫V max(0, n·ω) dω at unit normal n from one probe's visibility
  // coefficients, which use channel 0's functions: coefficientCount(0) of them.
  double visibility(const float* coefficients, const Vec3& n) const {
    double v;
    expand(primary_, coefficients, 1, n, &v);
    return v;
  }

  // Irradiance under a sky an engine swaps at run time: `rest` is one probe's coefficients less
  // its sky_direct grids' (the light that is not the sky's: interpolate it like coefficients),
  // `visibility` its visibility coefficients, `sky` the new sky (skyIrradiance).
  Rgb relitIrradiance(const float* rest, const float* visibility, const Vec3& n, const float* sky) const {
    return baker_decode::relitIrradiance(irradiance(rest, n), this->visibility(visibility, n), skyIrradiance(sky, n));
  }

  // ---- Radiance volumes ("signal": "radiance") ----

  // The Legendre series of the lobes' diffuse response: "diffuse_response"."coefficients" of the
  // function set in "baker.reconstruction". sg-N needs it; ad-cos2, ad-srbf and ambient-cube
  // have it built in (the file's equals it). False for other bases or more than
  // kMaxResponseTerms terms.
  bool setDiffuseResponse(const double* legendre, int terms) {
    const FunctionSetKind kind = primary_.kind;
    if (ycocg_ || terms < 1 || terms > kMaxResponseTerms || kind == FunctionSetKind::SphericalHarmonics ||
        kind == FunctionSetKind::IcosahedronLinear || kind == FunctionSetKind::IcosahedronBezier)
      return false;
    for (int l = 0; l < terms; ++l) primary_.response[l] = legendre[l];
    primary_.responseTerms = terms;
    return true;
  }

  // Whether irradianceFromRadiance() can decode: SH and the radial lobes (sg-N after
  // setDiffuseResponse). The piecewise Ambient Dice variants (ad-linear, ad-rgb, ad-rgb-flat,
  // ad-ycocg) have no closed-form response: their file states none, and only baker reads them.
  bool decodesRadiance() const {
    switch (primary_.kind) {
      case FunctionSetKind::SphericalHarmonics: return true;
      case FunctionSetKind::IcosahedronLobes:
      case FunctionSetKind::CubeLobes:
      case FunctionSetKind::SphericalGaussians:
      case FunctionSetKind::HemisphereLobes: return primary_.responseTerms > 0;
      default: return false;
    }
  }

  // RGB radiance L(d) arriving from unit direction d.
  Rgb radiance(const float* coefficients, const Vec3& d) const { return irradiance(coefficients, d); }

  // RGB irradiance E(n) = ∫ L(ω) max(0, n·ω) dω at unit normal n; zeros unless decodesRadiance().
  Rgb irradianceFromRadiance(const float* coefficients, const Vec3& n) const {
    double sums[3] = {0.0, 0.0, 0.0};
    if (ycocg_) return Rgb{0.0, 0.0, 0.0};
    expandIrradianceFromRadiance(primary_, coefficients, 3, n, sums);
    return Rgb{sums[0], sums[1], sums[2]};
  }

  // Sky visibility (1/π)∫V(ω) max(0, n·ω) dω from the stored V(ω) (channel 0's functions).
  double visibilityFromRadiance(const float* coefficients, const Vec3& n) const {
    double v = 0.0;
    if (!ycocg_) expandIrradianceFromRadiance(primary_, coefficients, 1, n, &v);
    return v / kPi;
  }

  // relitIrradiance for a radiance volume's coefficients; zeros unless decodesRadiance().
  Rgb relitIrradianceFromRadiance(const float* rest, const float* visibility, const Vec3& n, const float* sky) const {
    if (!decodesRadiance()) return Rgb{0.0, 0.0, 0.0};
    return baker_decode::relitIrradiance(irradianceFromRadiance(rest, n), visibilityFromRadiance(visibility, n),
                                         skyIrradiance(sky, n));
  }

  // Glossy specular for a GGX lobe (F0 = 1, α = roughness²) at unit normal n and unit view v
  // (towards the viewer): S = (1 − w)·L(r) + w·E(n)/π with w and the albedo from the table.
  Specular specular(const float* coefficients, const Vec3& n, const Vec3& v, double roughness,
                    const SpecularTable& table) const {
    const SpecularView view = specularView(n, v);
    Specular s;
    s.diffuseWeight = specularTableLookup(table.diffuseWeight, roughness, view.cosView);
    s.albedo = specularTableLookup(table.albedo, roughness, view.cosView);
    const Rgb mirror = radiance(coefficients, view.reflection), e = irradianceFromRadiance(coefficients, n);
    const double w = s.diffuseWeight, toRadiance = w / kPi;
    s.value = Rgb{(1.0 - w) * mirror.r + toRadiance * e.r, (1.0 - w) * mirror.g + toRadiance * e.g,
                  (1.0 - w) * mirror.b + toRadiance * e.b};
    return s;
  }

 private:
  // The digits after `prefix` in `name` as a number in [low, high], or −1.
  static int numberAfter(const char* name, const char* prefix, int low, int high) {
    const std::size_t length = std::strlen(prefix);
    if (std::strncmp(name, prefix, length) != 0) return -1;
    const char* digits = name + length;
    if (*digits == '\0' || std::strlen(digits) > 2 || (digits[0] == '0' && digits[1] != '\0')) return -1;
    int value = 0;
    for (const char* p = digits; *p; ++p) {
      if (*p < '0' || *p > '9') return -1;
      value = 10 * value + (*p - '0');
    }
    return value >= low && value <= high ? value : -1;
  }

  bool parse(const char* name, double sgSharpness) {
    const int shOrder = numberAfter(name, "sh-l", 0, kMaxShOrder);
    const int lobes = numberAfter(name, "sg-", 1, kMaxLobes);
    FunctionSet& f = primary_;
    if (shOrder >= 0) {
      f.kind = FunctionSetKind::SphericalHarmonics;
      f.shOrder = shOrder;
    } else if (lobes >= 1) {
      if (!(sgSharpness > 0.0)) return false;
      f.kind = FunctionSetKind::SphericalGaussians;
      f.lobeCount = lobes;
      f.sharpness = sgSharpness;
      for (int i = 0; i < lobes; ++i) {
        const Vec3 axis = sphericalFibonacciAxis(i, lobes);
        f.axes[3 * i] = axis.x, f.axes[3 * i + 1] = axis.y, f.axes[3 * i + 2] = axis.z;
      }
    } else if (std::strcmp(name, "ad-linear") == 0) {
      f.kind = FunctionSetKind::IcosahedronLinear;
      f.barycentrics = Barycentrics::Flat;
    } else if (std::strcmp(name, "ad-cos2") == 0 || std::strcmp(name, "ad-srbf") == 0) {
      // ad-srbf is the paper's 0.7·c² + 0.3·c⁴; both lobes normalised so the 12 sum to 1, using
      // Σ max(0, v̂·n)² = 2 and Σ max(0, v̂·n)⁴ = 6/5 over the vertices for every n.
      const bool paper = std::strcmp(name, "ad-srbf") == 0;
      const double w2 = paper ? 0.7 : 1.0, w4 = paper ? 0.3 : 0.0;
      const double scale = 1.0 / (2.0 * w2 + 1.2 * w4);
      f.kind = FunctionSetKind::IcosahedronLobes;
      setClampedLobe(f, scale * w2, scale * w4);
    } else if (std::strcmp(name, "ad-hemi9") == 0) {
      // ad-srbf's lobe on the icosahedron turned so that the face centre (1, 1, 1)/√3 points
      // along +Y (about (−1, 0, 1)/√2 through arccos(1/√3)), keeping the 9 vertices with y > −1/2.
      f.kind = FunctionSetKind::HemisphereLobes;
      setClampedLobe(f, 0.7 / 1.76, 0.3 / 1.76);
      const double c = 1.0 / std::sqrt(3.0), s = std::sqrt(2.0 / 3.0);
      const Vec3 k{-std::sqrt(0.5), 0.0, std::sqrt(0.5)};
      for (int i = 0; i < 12; ++i) {
        const Vec3 v = icosahedronVertex(i);
        const Vec3 turned = c * v + s * cross(k, v) + ((1.0 - c) * dot(k, v)) * k;
        if (turned.y <= -0.5) continue;
        f.axes[3 * f.lobeCount] = turned.x, f.axes[3 * f.lobeCount + 1] = turned.y, f.axes[3 * f.lobeCount + 2] = turned.z;
        f.lobeCount += 1;
      }
    } else if (std::strcmp(name, "ad-rgb") == 0 || std::strcmp(name, "ad-rgb-flat") == 0) {
      f.kind = FunctionSetKind::IcosahedronBezier;
      f.barycentrics = std::strcmp(name, "ad-rgb") == 0 ? Barycentrics::Spherical : Barycentrics::Flat;
    } else if (std::strcmp(name, "ad-ycocg") == 0) {
      ycocg_ = true;
      f.kind = FunctionSetKind::IcosahedronBezier;
      f.barycentrics = Barycentrics::Spherical;
      chroma_.kind = FunctionSetKind::IcosahedronLinear;
      chroma_.barycentrics = Barycentrics::Spherical;
    } else if (std::strcmp(name, "ambient-cube") == 0) {
      f.kind = FunctionSetKind::CubeLobes;
      const double square[3] = {kPi / 6.0, kPi / 4.0, kPi / 12.0};  // π(1 + x)²/8
      f.responseTerms = 3;
      for (int l = 0; l < 3; ++l) f.response[l] = square[l];
    } else {
      return false;
    }
    return true;
  }

  // cos2·c² + cos4·c⁴ lobes, with their diffuse response: max(0, t)² and max(0, t)⁴ respond with
  // π(1 + x)²/8 and π(1/16 + x/6 + x²/8 − x⁴/48) (docs/DECODERS.md), here as Legendre series.
  static void setClampedLobe(FunctionSet& f, double cos2, double cos4) {
    const double square[5] = {kPi / 6.0, kPi / 4.0, kPi / 12.0, 0.0, 0.0};
    const double fourth[5] = {kPi / 10.0, kPi / 6.0, kPi / 14.0, 0.0, -kPi / 210.0};
    f.cos2 = cos2;
    f.cos4 = cos4;
    f.responseTerms = 5;
    for (int l = 0; l < 5; ++l) f.response[l] = cos2 * square[l] + cos4 * fourth[l];
  }

  bool valid_ = false;
  bool ycocg_ = false;
  FunctionSet primary_;  // every channel's, or Y's for YCoCg
  FunctionSet chroma_;   // Co's and Cg's for YCoCg
};

// ---------------------------------------------------------------------------------------------
// Trilinear interpolation between probes. Probe (i, j, k) sits at origin + spacing·(i, j, k)
// and is stored as number i + nx·(j + ny·k). Interpolating coefficients interpolates the
// irradiance, since reconstruction is linear in them.

struct ProbeNeighbourhood {
  long long probe[8];  // corner c: +1 along x if c & 1, along y if c & 2, along z if c & 4
  double weight[8];
};

// The probes around `position` and their weights; outside the grid the nearest probes on its
// boundary are used, like a texture's clamp-to-edge.
inline ProbeNeighbourhood probeNeighbourhood(const Vec3& position, const Vec3& origin, double spacing, const int dims[3]) {
  const double grid[3] = {(position.x - origin.x) / spacing, (position.y - origin.y) / spacing,
                          (position.z - origin.z) / spacing};
  int low[3], high[3];
  double fraction[3];
  for (int a = 0; a < 3; ++a) {
    const double g = std::fmin(std::fmax(grid[a], 0.0), dims[a] - 1.0);
    low[a] = int(std::floor(g));
    if (low[a] > dims[a] - 2) low[a] = dims[a] > 1 ? dims[a] - 2 : 0;
    high[a] = dims[a] > 1 ? low[a] + 1 : 0;
    fraction[a] = g - low[a];
  }
  ProbeNeighbourhood n;
  for (int c = 0; c < 8; ++c) {
    const int i = (c & 1) ? high[0] : low[0], j = (c & 2) ? high[1] : low[1], k = (c & 4) ? high[2] : low[2];
    n.probe[c] = i + (long long)dims[0] * (j + (long long)dims[1] * k);
    n.weight[c] = ((c & 1) ? fraction[0] : 1.0 - fraction[0]) * ((c & 2) ? fraction[1] : 1.0 - fraction[1]) *
                  ((c & 4) ? fraction[2] : 1.0 - fraction[2]);
  }
  return n;
}

// out[i] = Σ_c weight[c]·probes[c][i] for i < count: one interpolated probe to decode.
inline void blendProbes(const float* const probes[8], const double weight[8], int count, float* out) {
  for (int i = 0; i < count; ++i) {
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) sum += weight[c] * probes[c][i];
    out[i] = float(sum);
  }
}

// ---------------------------------------------------------------------------------------------
// Leak-aware weights (docs/LEAKS.md): a volume with "baker.distance_map" holds per probe an N × N
// octahedral map of the mean and mean squared distance to the first surface, in units of the
// map's cap (value 2t and 2t + 1 of texel t = i + N·j: in a .vdb the R and G of the atlas grid
// distance_map at voxel (x·N + i, y·N + j, z) of probe (x, y, z); in EXR slices and .vdb files of
// format 6 the R and G of grid distance_map_NNN, t = NNN; in files of format 3, grids
// distance_moments_NNN). Multiply each corner's trilinear weight by leakWeight() and divide by the
// sum of the products.

struct DistanceMap {
  int size = 8;      // "size"
  double cap = 1.0;  // "cap", world units
};

// Octahedral coordinates in [0, 1]² of unit d, +Y up (the file's "encoding").
inline void octahedralEncode(const Vec3& d, double uv[2]) {
  const double l1 = std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z);
  double px = d.x / l1, pz = d.z / l1;
  if (d.y < 0.0) {
    const double fx = (1.0 - std::fabs(pz)) * (px < 0.0 ? -1.0 : 1.0), fz = (1.0 - std::fabs(px)) * (pz < 0.0 ? -1.0 : 1.0);
    px = fx, pz = fz;
  }
  uv[0] = 0.5 * (px + 1.0), uv[1] = 0.5 * (pz + 1.0);
}

// The weight in (0, 1] of the probe baked at `probe` (grid position plus its probe_offset) with
// distance moments `moments` (2·size² values), for a shading point on a surface of unit `normal`:
// 1 where its map reads open towards the point, else the back-face weight times Chebyshev's bound
// (docs/LEAKS.md).
inline double leakWeight(const DistanceMap& map, const float* moments, const Vec3& probe, const Vec3& point,
                         const Vec3& normal, double spacing) {
  const Vec3 biased = point + (0.25 * spacing) * normal;
  const Vec3 fromProbe = biased + (-1.0) * probe;
  const double r = std::sqrt(dot(fromProbe, fromProbe));
  if (!(r > 0.0) || !std::isfinite(r)) return 1.0;
  const Vec3 direction{fromProbe.x / r, fromProbe.y / r, fromProbe.z / r};
  double uv[2];
  octahedralEncode(direction, uv);
  const int n = map.size;
  int low[2];
  double f[2];
  for (int a = 0; a < 2; ++a) {
    const double x = uv[a] * n - 0.5;
    low[a] = int(std::floor(x));
    low[a] = low[a] < 0 ? 0 : low[a] > n - 2 ? n - 2 : low[a];
    f[a] = std::fmin(std::fmax(x - low[a], 0.0), 1.0);
  }
  double mean = 0.0, meanSquare = 0.0;
  bool open = true;
  for (int corner = 0; corner < 4; ++corner) {
    const int di = corner & 1, dj = corner >> 1;
    const double w = (di ? f[0] : 1.0 - f[0]) * (dj ? f[1] : 1.0 - f[1]);
    const int t = low[0] + di + n * (low[1] + dj);
    mean += w * moments[2 * t];
    meanSquare += w * moments[2 * t + 1];
    if (w > 0.0 && moments[2 * t] < 1.0f) open = false;
  }
  if (open) return 1.0;
  mean *= map.cap;
  meanSquare *= map.cap * map.cap;
  const double facing = 0.5 * (1.0 - dot(direction, normal));
  double weight = (facing * facing + 0.2) / 1.2;
  if (r > mean) {
    const double variance = std::fabs(meanSquare - mean * mean), beyond = r - mean;
    const double chebyshev = variance / (variance + beyond * beyond);
    weight *= chebyshev * chebyshev * chebyshev;
  }
  // The paper's floor and crush threshold, divided by 1.2 with its back-face weight.
  const double floor = 1e-6 / 1.2, crush = 0.2 / 1.2;
  if (!(weight >= floor)) weight = floor;
  if (weight < crush) weight *= weight * weight / (crush * crush);
  return weight;
}

// ---------------------------------------------------------------------------------------------
// Adaptive volumes ("baker.levels" > 1, docs/ADAPTIVE.md): levels of probes, coarsest first, each
// a grid as above holding only some bricks of 8³ probes (brick (bx, by, bz) holds probes
// 8·bx … 8·bx + 7 along x, and so on), and of each brick only some of its eight sub-bricks of 4³
// (sub-brick s = sx + 2·sy + 4·sz holds the probes with (i / 4) % 2 = sx, and so on). A point is
// decoded from the finest level whose probes around it (those with a non-zero weight) are all
// held; the level's border probes hold the coarser levels' values there, so the result is
// continuous where the level changes.

struct Level {
  Vec3 origin;
  double spacing;
  int dims[3];
  // Per brick, index bx + Bx·(by + By·bz) with B = ⌈dims / 8⌉: the sub-bricks the level holds of
  // it, bit s for sub-brick s (0xFF: the whole brick; 0: none; bits of sub-bricks beyond the
  // grid's edge are ignored). From a .vdb, the active voxels of the level's probe_state leaf; from
  // EXR slices, the atlas' "masks" (0xFF for each brick listed when there are none). Null: every
  // probe (a uniform volume, or a level that holds them all). Named bricksHeld, and non-zero per
  // held brick, before format 5: renamed so that such code no longer compiles.
  const unsigned char* subBricksHeld;
};

inline bool levelHoldsProbe(const Level& level, long long probe) {
  if (!level.subBricksHeld) return true;
  const long long nx = level.dims[0], ny = level.dims[1];
  const long long i = probe % nx, j = (probe / nx) % ny, k = probe / (nx * ny);
  const long long bx = (nx + 7) / 8, by = (ny + 7) / 8;
  const int subBrick = int((i / 4) % 2 + 2 * ((j / 4) % 2) + 4 * ((k / 4) % 2));
  return (level.subBricksHeld[i / 8 + bx * (j / 8 + by * (k / 8))] >> subBrick & 1) != 0;
}

struct LevelNeighbourhood {
  int level;  // which of the levels to read the probes of
  ProbeNeighbourhood around;
};

// The finest of `count` levels (coarsest first) whose probes around `position` are all held.
// When none is (only deep inside closed geometry), level 0 with its held probes' weights
// renormalised, and zero weights when it holds none of them.
inline LevelNeighbourhood finestLevelNeighbourhood(const Vec3& position, const Level* levels, int count) {
  for (int l = count - 1; l > 0; --l) {
    const ProbeNeighbourhood n = probeNeighbourhood(position, levels[l].origin, levels[l].spacing, levels[l].dims);
    bool held = true;
    for (int c = 0; c < 8 && held; ++c) held = n.weight[c] == 0.0 || levelHoldsProbe(levels[l], n.probe[c]);
    if (held) return LevelNeighbourhood{l, n};
  }
  LevelNeighbourhood result{0, probeNeighbourhood(position, levels[0].origin, levels[0].spacing, levels[0].dims)};
  double total = 0.0;
  for (int c = 0; c < 8; ++c) {
    if (!levelHoldsProbe(levels[0], result.around.probe[c])) result.around.weight[c] = 0.0;
    total += result.around.weight[c];
  }
  if (total > 0.0 && total != 1.0)
    for (int c = 0; c < 8; ++c) result.around.weight[c] /= total;
  return result;
}

}  // namespace baker_decode

#endif  // BAKER_IRRADIANCE_H
