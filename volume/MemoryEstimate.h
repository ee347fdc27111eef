#pragma once
#include <cstdint>

#include "basis/Basis.h"
#include "volume/ProbeGrid.h"

namespace baker {

// Bytes a bake of `grid` in `basis` holds at its peak: every probe's coefficients, sky
// visibility, state and offset, and as much again while the writer lays them out as grids.
// In double precision, so that no grid overflows it.
double volumeMemoryBytes(const ProbeGrid& grid, const Basis& basis);

// This machine's physical memory in bytes (the largest value when the system does not say).
std::uint64_t physicalMemoryBytes();

// InputError with the estimate in bytes when a bake of `grid` needs more than `availableBytes`:
// refused before anything is traced or allocated, rather than failing hours later.
void requireVolumeFitsInMemory(const ProbeGrid& grid, const Basis& basis, std::uint64_t availableBytes);

}  // namespace baker
