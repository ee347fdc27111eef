#pragma once
#include <string>

#include "basis/Basis.h"
#include "volume/ProbeGrid.h"

namespace baker {

// What a reader of an adaptive volume checks of each level before it allocates it, the same in
// every format: InputError naming `path`.
class LevelChecks {
 public:
  LevelChecks(const Basis& basis, std::string path) : basis_(basis), path_(std::move(path)) {}
  // Level `level`'s grid: a valid size and, below level 0, on the lattice of level − 1's grid
  // (LevelGrids.h). `key` names where the file gives it.
  void grid(int level, const ProbeGrid& grid, const std::string& key);
  // The margin the placement used (`key` names it in the file): 1 to 4 cells.
  void margin(int cells, const std::string& key) const;
  // Adds a level's held bricks: refused when the levels read so far hold more probes than a volume
  // may or than this machine's memory.
  void held(int level, std::size_t bricks);

 private:
  const Basis& basis_;
  std::string path_;
  ProbeGrid parent_;
  double held_ = 0.0;
};

}  // namespace baker
