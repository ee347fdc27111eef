#pragma once
#include <cstdint>

namespace baker {

// Where a probe was baked: where the grid puts it, moved out of geometry, or not at all (found
// inside geometry, and filled from its neighbours). bake/ProbeValidity decides it. A probe of an
// adaptive volume on the border of its level's bricks is not traced: it holds the coarser
// levels' interpolated value there, so that no seam shows where the level changes.
enum class ProbeState : std::uint8_t { Invalid = 0, Valid = 1, Relocated = 2, Interpolated = 3 };
constexpr int kProbeStateCount = 4;

// "valid", "relocated", "invalid" or "interpolated": the word reports and JSON use.
const char* probeStateName(ProbeState state);

}  // namespace baker
