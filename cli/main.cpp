#include "cli/BakeCommand.h"

// `baker SCENE ...` bakes; later commands are dispatched on their first word here.
int main(int argc, char** argv) { return baker::runBakeCommand(argc, argv); }
