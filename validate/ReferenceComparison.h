#pragma once
#include <cstdint>
#include <vector>

#include "validate/IrradianceError.h"
#include "validate/ReferencePanoramas.h"
#include "validate/VolumeComparison.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// One reference probe and how far the volume is from it there.
struct ReferenceProbeError {
  ReferenceProbe probe;
  double relativeError = 0.0;
  double maxAbsoluteError = 0.0;
  double referenceMean = 0.0;
};

// A volume against path-traced reference panoramas: at each reference probe inside the region the
// volume's cells cover, the exact E(n) of its panorama against the volume read there as an engine
// reads it (an adaptive volume's finest level holding the probes around it, trilinearly), at the
// comparison normals (validate/IrradianceError.h).
struct ReferenceComparison {
  std::int64_t probesCompared = 0;
  std::int64_t probesOutside = 0;
  RelativeErrors errors;  // perProbe in the order of the compared probes
  std::vector<ReferenceProbeError> worst;
  // Bake settings that make the volume differ from the reference by design (`reference` says what
  // the panoramas assume, `candidate` what the volume was baked with).
  std::vector<MetadataDifference> settingDifferences;
};

ReferenceComparison compareWithReference(const AdaptiveVolume& volume, const ReferenceSet& set, std::size_t worstCount);

}  // namespace baker
