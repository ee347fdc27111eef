#pragma once

namespace baker {

// `baker preview VOLUME --out FILE.png [--probe x,y,z [--reference DIR]] [--exposure X] [--json]`:
// a PNG of the volume's middle slices, probe markers, a colour bar and optionally one probe's
// irradiance sphere beside a reference panorama (layout in validate/PreviewImage.h). Prints the
// legend's numbers (exposure, colour-bar range, slices). argv[0] is "preview".
int runPreviewCommand(int argc, char** argv);

}  // namespace baker
