#pragma once
#include <string>
#include <vector>

#include "scene/ColorImage.h"

namespace baker {

// Larger images than this many texels (8192², 512 MiB at 16-bit RGBA while decoding) are
// refused before their pixels are allocated.
constexpr long long kMaxTextureTexels = 1ll << 26;

// Decodes a PNG or JPEG held in memory (the bytes of a glTF image, whichever way the file
// stored them) into a colour texture: grey, grey + alpha, RGB or RGBA. Throws InputError
// with `what` (the glTF path of the image) and the reason when it cannot.
ColorImage decodeColorImage(const std::vector<unsigned char>& encoded, const std::string& what);

}  // namespace baker
