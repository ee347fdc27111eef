#include "formats/HalfFloat.h"

#include <Imath/half.h>

namespace baker {

std::uint16_t halfBits(float value) { return Imath::half(value).bits(); }

}  // namespace baker
