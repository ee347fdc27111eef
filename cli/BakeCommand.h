#pragma once

namespace baker {

// `baker SCENE [--basis NAME] [--out FILE.vdb|DIR] [--format vdb|exr] [--precision half|float] [--spacing M] [--rays N] [--bounces N] [--seed S]
//  [--no EFFECT ...] [--threads N] [--json] [--scene N] [--env FILE [--env-intensity X]
//  [--env-rotation DEG] | --sky R,G,B]`
int runBakeCommand(int argc, char** argv);

}  // namespace baker
