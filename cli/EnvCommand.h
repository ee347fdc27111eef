#pragma once

namespace baker {

// `baker env PROBE.hdr --basis NAME [--json] [--out-dir DIR] [--sg-sharpness L]`: how well a
// basis represents a lat-long environment's irradiance, against the exact texel sum; with
// `--signal radiance [--upward] [--hemisphere-axis X,Y,Z]`, its radiance, read as diffuse and
// specular.
// argv[0] is "env".
int runEnvCommand(int argc, char** argv);

}  // namespace baker
