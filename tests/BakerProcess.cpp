#include "tests/BakerProcess.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace baker::test {
namespace {

std::string takeText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::filesystem::remove(path);
  return text.str();
}

}  // namespace

ProcessResult runBaker(const std::string& dir, const std::string& args) { return runBakerUnder(dir, "", args); }

ProcessResult runBakerUnder(const std::string& dir, const std::string& launcher, const std::string& args) {
  const std::string outFile = dir + "/.stdout.txt", errFile = dir + "/.stderr.txt";
  const std::string command = "cd '" + dir + "' && " + launcher + " '" BAKER_BINARY "' " + args + " > '" + outFile +
                              "' 2> '" + errFile + "'";
  const int status = std::system(command.c_str());
  ProcessResult run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = takeText(outFile);
  run.err = takeText(errFile);
  return run;
}

std::string shellWords(const std::vector<std::string>& args) {
  std::string words;
  for (const std::string& arg : args) {
    std::string quoted = "'";
    for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    words += quoted + "' ";
  }
  return words;
}

ProcessResult runBaker(const std::string& dir, const std::vector<std::string>& args) {
  return runBaker(dir, shellWords(args));
}

}  // namespace baker::test
