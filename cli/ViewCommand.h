#pragma once

namespace baker {

// `baker view VOLUME [--gltf SCENE] --out DIR [--serve [PORT]] [--json]`: a page that shows the
// volume in a browser, with its scene (viewer/ViewerPage.h; the page itself is web/viewer/).
int runViewCommand(int argc, char** argv);

}  // namespace baker
