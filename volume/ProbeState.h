#pragma once
#include <cstdint>

namespace baker {

// Where a probe was baked: where the grid puts it, moved out of geometry, or not at all (found
// inside geometry, and filled from its neighbours). bake/ProbeValidity decides it.
enum class ProbeState : std::uint8_t { Invalid = 0, Valid = 1, Relocated = 2 };

// "valid", "relocated" or "invalid": the word reports and JSON use.
const char* probeStateName(ProbeState state);

}  // namespace baker
