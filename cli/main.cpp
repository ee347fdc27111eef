#include <fmt/format.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "cli/AccuracyCommand.h"
#include "cli/BakeCommand.h"
#include "cli/BasesCommand.h"
#include "cli/EnvCommand.h"
#include "cli/InfoCommand.h"
#include "cli/MergeCommand.h"
#include "cli/PreviewCommand.h"
#include "cli/ProbeCommand.h"
#include "cli/RelightCommand.h"
#include "cli/RenderCommand.h"
#include "cli/ValidateCommand.h"
#include "cli/ViewCommand.h"
#include "cli/VolumeCommands.h"

namespace {

struct Command {
  const char* name;
  const char* usage;
  const char* summary;
  int (*run)(int argc, char** argv);
};

// Every command, in the order `baker help` lists them. "bake" is also what `baker SCENE` runs.
const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      {"bake", "baker SCENE [OPTIONS]", "bake an irradiance volume for a glTF scene", baker::runBakeCommand},
      {"merge", "baker merge OUT PART...", "the parts of a bake cut into shards, as one volume",
       baker::runMergeCommand},
      {"relight", "baker relight VOLUME --env NEW.hdr --out OUT", "a volume under another sky, without a rebake",
       baker::runRelightCommand},
      {"probe", "baker probe SCENE --at x,y,z", "bake single probes and print what they receive",
       baker::runProbeCommand},
      {"info", "baker info SCENE", "what baker loads from a scene and which effects a bake simulates",
       baker::runInfoCommand},
      {"inspect", "baker inspect VOLUME", "what a volume holds", baker::runInspectCommand},
      {"sample", "baker sample VOLUME --at P --normal N", "irradiance and sky visibility at a point, for a normal",
       baker::runSampleCommand},
      {"preview", "baker preview VOLUME --out PNG", "a PNG of a volume's middle slices", baker::runPreviewCommand},
      {"render", "baker render SCENE --eye P --look-at Q", "a scene's surfaces lit by traced irradiance and by a volume",
       baker::runRenderCommand},
      {"view", "baker view VOLUME --out DIR", "a page that shows a volume and its scene in a browser",
       baker::runViewCommand},
      {"validate", "baker validate REF NEW", "compare a volume with another, or with Cycles references",
       baker::runValidateCommand},
      {"accuracy", "baker accuracy SCENE", "error against bake time for bases × ray counts × bounces",
       baker::runAccuracyCommand},
      {"env", "baker env PROBE.hdr --basis B", "a light probe's irradiance in a basis, against the exact sum",
       baker::runEnvCommand},
      {"bases", "baker bases", "every basis with its coefficient counts", baker::runBasesCommand},
  };
  return all;
}

const Command* findCommand(const char* name) {
  for (const Command& c : commands())
    if (std::strcmp(c.name, name) == 0) return &c;
  return nullptr;
}

int printOverview() {
  std::cout << "baker " BAKER_VERSION ": irradiance volumes for glTF 2.0 scenes.\n\nUsage:\n";
  for (const Command& c : commands()) std::cout << fmt::format("  {:<38} {}\n", c.usage, c.summary);
  std::cout << "\n`baker help COMMAND` or `baker COMMAND --help` shows a command's options "
               "(`baker help bake`: the bake's).\n";
  return 0;
}

// `baker help COMMAND`: the command's own --help.
int runHelp(int argc, char** argv) {
  if (argc < 2) return printOverview();
  const Command* command = findCommand(argv[1]);
  if (!command) {
    std::cerr << fmt::format("baker help: error: '{}' is not a command; `baker help` lists them\n", argv[1]);
    return 2;
  }
  char help[] = "--help";
  char* args[] = {argv[1], help, nullptr};
  return command->run(2, args);
}

}  // namespace

// `baker COMMAND ...` runs a named command; anything else (`baker SCENE ...`) bakes.
int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) return printOverview();
  if (std::strcmp(argv[1], "help") == 0) return runHelp(argc - 1, argv + 1);
  if (const Command* command = findCommand(argv[1])) return command->run(argc - 1, argv + 1);
  return baker::runBakeCommand(argc, argv);
}
