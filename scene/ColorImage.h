#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scene/HugePageAllocator.h"

namespace baker {

// glTF sampler wrap modes, per texture axis.
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

// How a texture is read. There are no mipmaps: a bake looks textures up at ray hits, which
// have no screen-space footprint, so minFilter has nothing to choose and only magFilter counts
// (NEAREST picks the texel containing the point, anything else is bilinear).
struct SamplerState {
  Wrap wrapS = Wrap::Repeat;
  Wrap wrapT = Wrap::Repeat;
  bool nearest = false;
};

// A decoded colour texture (base colour or emissive): RGB sRGB-encoded and alpha linear, as
// glTF stores them. Lookups return linear RGBA. Row 0 is the top of the image, which is where
// glTF's v = 0 lies, so uv (0, 0) is the top-left corner of texel (0, 0).
//
// 8-bit images keep their bytes (a quarter of the memory of floats; the sRGB curve is a table
// lookup); deeper images are decoded to linear floats once.
class ColorImage {
 public:
  ColorImage() = default;
  static ColorImage fromBytes(int width, int height, std::vector<std::uint8_t> rgba);
  static ColorImage fromLinear(int width, int height, std::vector<float> rgba);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t memoryBytes() const { return bytes_.size() + linear_.size() * sizeof(float); }

  // Linear RGBA of texel (x, y), both in range.
  Eigen::Vector4f texel(int x, int y) const;

  // The texels a lookup at glTF texture coordinates `uv` reads, wrapped as `sampler` says
  // (x0 = x1 and y0 = y1 when nearest), and the bilinear weights of the second column and
  // row. Non-finite coordinates read as 0.
  struct Footprint {
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    float ax = 0.0f, ay = 0.0f;
    bool nearest = false;
  };
  Footprint footprint(const Eigen::Vector2f& uv, const SamplerState& sampler) const;
  // Starts loading a footprint's texels into the cache and returns at once: a bake looks
  // textures up at scattered points, and a batch of lookups that announces itself first waits
  // for its cache misses together instead of one after another. The same footprint is then
  // read with sample(), so that finding the texels is paid once.
  void prefetch(const Footprint& footprint) const;
  // Linear RGBA of a footprint, filtered by its weights.
  Eigen::Vector4f sample(const Footprint& footprint) const;
  // Linear RGBA at `uv`, wrapped and filtered as `sampler` says.
  Eigen::Vector4f sample(const Eigen::Vector2f& uv, const SamplerState& sampler) const {
    return sample(footprint(uv, sampler));
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t, HugePageAllocator<std::uint8_t>> bytes_;
  std::vector<float, HugePageAllocator<float>> linear_;
};

// The exact sRGB transfer curve, encoded value in [0, 1] to linear.
float srgbToLinear(float encoded);

}  // namespace baker
