#pragma once
#include <cstdint>

namespace baker {

// Peak resident memory of this process so far, in bytes.
std::uint64_t peakMemoryBytes();

}  // namespace baker
