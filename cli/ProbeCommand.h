#pragma once

namespace baker {

// `baker probe SCENE --at x,y,z [--at ...] [bake options] [--json]`: bakes just those probes and
// prints, per probe, its coefficients, the irradiance E for the normals ±X, ±Y, ±Z (as the
// basis reconstructs it, and straight from the samples), its sky visibility and validity.
int runProbeCommand(int argc, char** argv);

}  // namespace baker
