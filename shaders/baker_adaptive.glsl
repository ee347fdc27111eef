// baker_adaptive.glsl — which probes to blend at a point of an adaptive volume (docs/ADAPTIVE.md),
// the C++ header's finestLevelNeighbourhood on the GPU. Written in the common subset of GLSL ES
// 3.00 (WebGL 2) and GLSL 4.50: no #version line and no uniforms; include it before the code that
// reads the probes (baker_irradiance.glsl's BAKER_ADAPTIVE_FETCH, or baker_irradiance_webgl.js's
// BAKER_ADAPTIVE_WEBGL_GLSL). Needs highp int (slot arithmetic passes 16 bits) and the
// indirection texture's filters NEAREST without mipmaps, or texelFetch reads an incomplete
// texture as 0.
//
// Textures (docs/DECODERS.md "Adaptive volumes on the GPU"):
// - The pool: every level's held bricks of 8³ probes, level after level (coarsest first), each
//   level's in the order of its "atlas" "bricks"; pool slot s holds one brick.
// - The indirection texture: unsigned integers (R32UI), one texel per brick of every level, the
//   levels stacked along z: texel (bx, by, brickZ[l] + bz) is 0 where the level does not hold
//   brick (bx, by, bz); otherwise its low 24 bits are 1 + the brick's pool slot and its high 8 bits
//   the sub-bricks of 4³ the level holds of it (bit s = sx + 2·sy + 4·sz for the probes with
//   (i / 4) % 2 = sx and so on; 0xFF the whole brick). Its x and y extents are the largest
//   level's brick counts.
// Level l's probe (i, j, k) sits at origin[l] + spacing[l]·(i, j, k), for i < dims[l].x and so on.

#define BAKER_MAX_LEVELS 4

// Corner c (+1 along x if c & 1, along y if c & 2, along z if c & 4): its probe as a pool slot
// and its place in that brick (each 0–7), and its trilinear weight. A corner of weight 0 may
// point at any slot: skip it.
struct BakerCorners {
  int level;
  int slot[8];
  ivec3 local[8];
  float weight[8];
};

// 1 + the pool slot of the brick holding level l's probe p, or 0 when the level does not hold it.
uint bakerHeldSlot(highp usampler3D indirection, int brickZ, ivec3 p) {
  ivec3 brick = p / 8;
  highp uint texel = texelFetch(indirection, ivec3(brick.xy, brickZ + brick.z), 0).r;
  ivec3 side = (p / 4) % 2;
  uint subBrick = uint(side.x + 2 * side.y + 4 * side.z);
  return ((texel >> (24u + subBrick)) & 1u) != 0u ? texel & 0xFFFFFFu : 0u;
}

// The probes around `position` on level l's grid, clamped to its boundary as a texture's
// clamp-to-edge, with their weights (the header's probeNeighbourhood).
void bakerLevelCell(vec3 position, vec3 origin, float spacing, ivec3 dims, out ivec3 low, out ivec3 high,
                    out vec3 fraction) {
  vec3 last = vec3(dims - 1);
  vec3 g = clamp((position - origin) / spacing, vec3(0.0), last);
  low = ivec3(floor(g));
  for (int a = 0; a < 3; ++a) {
    if (low[a] > dims[a] - 2) low[a] = dims[a] > 1 ? dims[a] - 2 : 0;
    high[a] = dims[a] > 1 ? low[a] + 1 : 0;
  }
  fraction = g - vec3(low);
}

// The finest level whose probes of non-zero weight around `position` are all held; when none is
// (only deep inside closed geometry), level 0 with its held probes' weights renormalised, or all
// weights 0 when it holds none of them.
BakerCorners bakerAdaptiveCorners(vec3 position, highp usampler3D indirection, int levelCount,
                                  vec3 origin[BAKER_MAX_LEVELS], float spacing[BAKER_MAX_LEVELS],
                                  ivec3 dims[BAKER_MAX_LEVELS], int brickZ[BAKER_MAX_LEVELS]) {
  BakerCorners corners;
  for (int l = BAKER_MAX_LEVELS - 1; l >= 0; --l) {
    if (l >= levelCount) continue;
    ivec3 low, high;
    vec3 f;
    bakerLevelCell(position, origin[l], spacing[l], dims[l], low, high, f);
    bool held = true;
    float total = 0.0;
    for (int c = 0; c < 8; ++c) {
      ivec3 p = ivec3((c & 1) != 0 ? high.x : low.x, (c & 2) != 0 ? high.y : low.y, (c & 4) != 0 ? high.z : low.z);
      float w = ((c & 1) != 0 ? f.x : 1.0 - f.x) * ((c & 2) != 0 ? f.y : 1.0 - f.y) * ((c & 4) != 0 ? f.z : 1.0 - f.z);
      uint slot = bakerHeldSlot(indirection, brickZ[l], p);
      if (slot == 0u && w != 0.0) {
        held = false;
        w = 0.0;
      }
      corners.slot[c] = slot == 0u ? 0 : int(slot) - 1;
      corners.local[c] = p - 8 * (p / 8);
      corners.weight[c] = w;
      total += w;
    }
    corners.level = l;
    if (held && l > 0) return corners;
    if (l == 0 && total > 0.0)  // as the header does, also when every corner is held
      for (int c = 0; c < 8; ++c) corners.weight[c] /= total;
  }
  return corners;
}
