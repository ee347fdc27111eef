#pragma once
#include <cstdint>

#include "basis/Basis.h"
#include "volume/ProbeGrid.h"

namespace baker {

// Bytes a volume of `probes` probes in `basis` holds at its peak: every probe's coefficients (and
// their directly seen sky's part), sky visibility, distance moments (`distanceValues` per probe), state and offset, and as much again
// while the writer or a merge lays them out. In double precision, so that no grid overflows it.
double volumeMemoryBytes(double probes, const Basis& basis, int distanceValues = 0);

// This machine's physical memory in bytes (the largest value when the system does not say).
std::uint64_t physicalMemoryBytes();

// Bytes one shard of `shardCount` of a bake of `grid` holds at its peak: its share of the
// probes' values (volumeMemoryBytes), and when cut into shards the per-brick tables that find them.
double bakeMemoryBytes(const ProbeGrid& grid, int shardCount, const Basis& basis, int distanceValues = 0);

// SettingError "spacing" with the estimate in bytes when one shard of `shardCount` (1: the
// whole bake) of `grid` needs more than `availableBytes`: refused before anything is traced or
// allocated, rather than failing hours later.
void requireVolumeFitsInMemory(const ProbeGrid& grid, int shardCount, const Basis& basis, std::uint64_t availableBytes,
                               int distanceValues = 0);

}  // namespace baker
