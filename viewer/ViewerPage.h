#pragma once
#include <string>

#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// What `baker view` writes: a directory any browser opens as it is (or through a local server),
// with
//  - index.html and viewer.js: the page, three.js bundled into it at build time (web/viewer/);
//  - volume.json and volume.bin: the volume's levels (one for a uniform volume), basis and
//    metadata, and each level's values (coefficients, sky visibility, probe states, offsets,
//    distance moments) for the probes it holds, with where they are on its grid, as
//    little-endian binary;
//  - scene/: the glTF scene with the files it refers to, when there is one.
// The directory appears only when complete, and replaces only a page this tool wrote.
struct ViewerPage {
  std::string volumePath;  // for the page's title and the settings shown
  std::string scenePath;   // "" for a page without the scene
  std::string outDirectory;
};

// The glTF scene of a volume: `given` when not empty (InputError if it is missing), else the
// scene its metadata names when that file is beside the volume, else "".
std::string sceneOfVolume(const Volume& volume, const std::string& volumePath, const std::string& given);

// Writes the page. InputError naming the file for a scene it cannot copy or an output it must not
// replace; std::runtime_error when the page's bundle is missing from this installation.
void writeViewerPage(const AdaptiveVolume& levels, const ViewerPage& page);

// Where the built page (index.html, viewer.js) is: $BAKER_VIEWER_DIR, else viewer/ beside the
// executable, else the build tree's. std::runtime_error naming where it looked.
std::string viewerBundleDirectory();

}  // namespace baker
