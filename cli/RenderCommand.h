#pragma once

namespace baker {

// `baker render SCENE [bake options] --eye P --look-at Q [--volume V] --out PNG [--json]`: the
// scene's surfaces seen through a pinhole camera, each pixel showing the irradiance its point
// receives: traced there with the bake options (the reference), then, with a volume, read from it
// trilinearly and leak-aware, side by side, with how far each reading is from the traced one
// (validate/SurfaceView.h). argv[0] is "render".
int runRenderCommand(int argc, char** argv);

}  // namespace baker
