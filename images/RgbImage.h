#pragma once
#include <string>
#include <vector>

namespace baker {

// A float RGB image: rows from the top, pixels left to right, channels interleaved.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // width · height · 3

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 3, 0.0f) {}
  float* pixel(int row, int column) { return &pixels[(std::size_t(row) * width + column) * 3]; }
  const float* pixel(int row, int column) const { return &pixels[(std::size_t(row) * width + column) * 3]; }
};

// Any image OpenImageIO reads (Radiance .hdr, OpenEXR, ...), as float RGB: the first three
// channels, or one grey channel repeated. InputError naming `path` when it is missing,
// unreadable, or has two channels.
RgbImage readRgbImage(const std::string& path);

// Both writers write exactly `path` whatever its extension (callers pass an AtomicFile's
// temporary name) and throw InputError naming it on failure.
// 32-bit float OpenEXR, values as they are.
void writeExr(const RgbImage& image, const std::string& path);
// 8-bit PNG: each value times `exposure`, clamped to [0, 1], then encoded with the exact sRGB
// transfer curve (no tone curve, so over-exposed values clip to white).
void writeSrgbPng(const RgbImage& image, double exposure, const std::string& path);

}  // namespace baker
