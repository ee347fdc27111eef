// `baker help`, `baker --help`: every command listed; `baker help COMMAND` and `baker COMMAND
// --help`: that command's options; an unknown one is an error naming it.
#include <gtest/gtest.h>

#include "tests/BakerProcess.h"
#include "tests/TestData.h"

namespace baker {
namespace {

const char* const kCommands[] = {"probe", "info", "inspect", "sample", "preview", "render", "validate", "accuracy", "env", "bases"};

TEST(CommandHelp, HelpListsEveryCommand) {
  const std::string dir = test::makeTempDir("command-help");
  for (const char* args : {"help", "--help", "-h", ""}) {
    const test::ProcessResult run = test::runBaker(dir, args);
    EXPECT_EQ(run.exitCode, 0) << args << ": " << run.err;
    EXPECT_NE(run.out.find("baker SCENE [OPTIONS]"), std::string::npos) << args << ": " << run.out;
    for (const char* command : kCommands)
      EXPECT_NE(run.out.find(std::string("baker ") + command), std::string::npos) << args << " lists no " << command;
  }
}

TEST(CommandHelp, EachCommandShowsItsOptionsBothWays) {
  const std::string dir = test::makeTempDir("command-help-each");
  const std::pair<const char*, const char*> expected[] = {
      {"bake", "--quality"}, {"probe", "--at"}, {"info", "--sky"},        {"inspect", "--json"}, {"sample", "--normal"},
      {"preview", "--exposure"}, {"render", "--look-at"}, {"validate", "--tolerance"}, {"accuracy", "--reference-rays"},
      {"env", "--sg-sharpness"}, {"bases", "--json"}};
  for (const auto& [command, option] : expected) {
    const test::ProcessResult help = test::runBaker(dir, std::string("help ") + command);
    EXPECT_EQ(help.exitCode, 0) << command << ": " << help.err;
    EXPECT_NE(help.out.find(option), std::string::npos) << "baker help " << command << ": " << help.out;
    const test::ProcessResult own = test::runBaker(dir, std::string(command) + " --help");
    EXPECT_EQ(own.exitCode, 0) << command << ": " << own.err;
    EXPECT_EQ(own.out, help.out) << command;
  }
}

TEST(CommandHelp, AnUnknownCommandIsNamed) {
  const std::string dir = test::makeTempDir("command-help-unknown");
  const test::ProcessResult run = test::runBaker(dir, "help nosuch");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("'nosuch' is not a command"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace baker
