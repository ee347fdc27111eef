#include "formats/HalfFloat.h"

#include <Imath/half.h>

namespace baker {

std::uint16_t halfBits(float value) { return Imath::half(value).bits(); }

float halfValue(std::uint16_t bits) {
  Imath::half h;
  h.setBits(bits);
  return float(h);
}

}  // namespace baker
