#pragma once

namespace baker {

// `baker bases [--json]`: every basis with its coefficient counts, Gram conditioning and SH
// reproduction norms (paper eq. 9) for L = 1…4 under both definitions.
int runBasesCommand(int argc, char** argv);

}  // namespace baker
