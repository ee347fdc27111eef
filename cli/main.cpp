#include <cstring>

#include "cli/AccuracyCommand.h"
#include "cli/BakeCommand.h"
#include "cli/BasesCommand.h"
#include "cli/EnvCommand.h"
#include "cli/InfoCommand.h"
#include "cli/PreviewCommand.h"
#include "cli/ProbeCommand.h"
#include "cli/ValidateCommand.h"
#include "cli/VolumeCommands.h"

// `baker COMMAND ...` runs a named command; anything else (`baker SCENE ...`) bakes.
int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "bases") == 0) return baker::runBasesCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "env") == 0) return baker::runEnvCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "info") == 0) return baker::runInfoCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "accuracy") == 0) return baker::runAccuracyCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "sample") == 0) return baker::runSampleCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "inspect") == 0) return baker::runInspectCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "probe") == 0) return baker::runProbeCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "validate") == 0) return baker::runValidateCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "preview") == 0) return baker::runPreviewCommand(argc - 1, argv + 1);
  return baker::runBakeCommand(argc, argv);
}
