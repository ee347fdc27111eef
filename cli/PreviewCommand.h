#pragma once

namespace baker {

// `baker preview VOLUME --out FILE.png [--probe x,y,z [--reference DIR]] [--exposure X] [--json]`:
// a PNG of the volume's middle slices, probe markers, a colour bar and optionally one probe's
// irradiance sphere beside a reference panorama (layout in validate/PreviewImage.h). Prints the
// legend's numbers (exposure, colour-bar range, slices). An adaptive volume's slices lie on its
// finest level's grid, and the legend counts the cells each level's values fill (cells_by_level
// in --json). argv[0] is "preview".
int runPreviewCommand(int argc, char** argv);

}  // namespace baker
