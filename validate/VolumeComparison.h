#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "validate/IrradianceError.h"
#include "volume/AdaptiveVolume.h"
#include "volume/SkyHarmonics.h"
#include "volume/Volume.h"

namespace baker {

// One probe of the reference volume and how far the new volume is from it there.
struct ComparedProbe {
  int level = 0;  // of an adaptive volume; index is on that level's grid
  Eigen::Vector3i index{0, 0, 0};
  Eigen::Vector3d position{0, 0, 0};  // grid position in the world (without probe_offset)
  double relativeError = 0.0;
  double maxAbsoluteError = 0.0;
  double referenceMean = 0.0;
};

struct ValidityChange {
  int level = 0;
  Eigen::Vector3i index{0, 0, 0};
  Eigen::Vector3d position{0, 0, 0};
  ProbeState reference = ProbeState::Valid;
  ProbeState candidate = ProbeState::Valid;
};

// A field of the metadata (basis, grid, a bake setting) whose values differ; "" for absent.
struct MetadataDifference {
  std::string field;
  std::string reference;
  std::string candidate;
};

// Two volumes compared probe by probe of the reference, in reconstructed irradiance at the
// comparison normals (validate/IrradianceError.h), each volume through its own basis. When the
// grids are the same (every level's, for adaptive volumes), a reference probe meets the new
// volume's probe of the same level and index; otherwise, or where the new volume does not hold
// that probe, the new volume read at the reference probe's position as an engine reads it (the
// finest level holding the probes around it, trilinearly), and only reference probes inside the
// region the new volume's cells cover are compared (none: the grids do not overlap).
struct VolumeComparison {
  bool adaptive = false;  // the reference has levels: probes are named by level and index
  bool gridsMatch = false;
  std::int64_t probesCompared = 0;
  std::int64_t probesOutside = 0;  // reference probes outside the new volume's cells
  RelativeErrors errors;           // perProbe in the order of the compared probes
  std::vector<ComparedProbe> worst;
  bool validityCompared = false;  // probe by probe only when the grids match
  std::vector<ValidityChange> validityChanges;
  // max |V_new(n) − V_ref(n)| of sky visibility over compared probes and normals; absent when
  // either volume stores no visibility.
  std::optional<double> skyVisibilityMaxDifference;
  std::vector<MetadataDifference> metadataDifferences;
  // Adaptive volumes on the same grids: the probes each holds that the other does not, level by
  // level (geometry that moved places other bricks). Absent for uniform volumes or other grids.
  struct Placement {
    std::int64_t referenceOnly = 0;
    std::int64_t newOnly = 0;
  };
  std::optional<Placement> placement;
};

// A sky to read the new volume under as decoders relight at run time (VolumeReconstruction::
// relitIrradiance), rather than as stored; `name` names the volume in errors.
struct RunTimeSky {
  const SkyHarmonics* sky = nullptr;
  std::string name;
};

// With a run-time sky, InputError when the new volume keeps no sky_direct grids. A uniform
// volume is the case of one level.
VolumeComparison compareVolumes(const AdaptiveVolume& reference, const AdaptiveVolume& candidate, std::size_t worstCount,
                                const RunTimeSky& runTimeSky = {});

// Whether `grid` puts probes exactly where `other` does.
bool sameGrid(const ProbeGrid& grid, const ProbeGrid& other);

// Whether `position` lies in the region the grid's cells cover: each probe at the centre of a
// cell of the grid's spacing, the region an engine's 3D texture spans.
bool insideCells(const ProbeGrid& grid, const Eigen::Vector3d& position);

}  // namespace baker
