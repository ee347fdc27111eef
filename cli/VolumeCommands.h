#pragma once

namespace baker {

// `baker sample VOLUME --at x,y,z --normal x,y,z [--json]`: the volume's irradiance E and sky
// visibility at a world position for a normal, interpolated and reconstructed as an engine would.
int runSampleCommand(int argc, char** argv);

// `baker inspect VOLUME [--json]`: what a volume holds: grid, basis, grids, value ranges,
// probe states, bytes.
int runInspectCommand(int argc, char** argv);

}  // namespace baker
