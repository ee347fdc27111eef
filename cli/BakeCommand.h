#pragma once

namespace baker {

// `baker SCENE [--basis NAME] [--out FILE.vdb] [--spacing M] [--rays N] [--threads N] [--json]`
int runBakeCommand(int argc, char** argv);

}  // namespace baker
