#pragma once
#include <string>
#include <vector>

namespace baker::test {

struct ProcessResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

// Runs the real baker binary with `args` (a shell word list) in `dir`, as a user would.
ProcessResult runBaker(const std::string& dir, const std::string& args);
// The same with each argument quoted for the shell.
ProcessResult runBaker(const std::string& dir, const std::vector<std::string>& args);
// The baker binary started by `launcher`, a shell command prefix ("mpirun -np 2"; "" for none).
ProcessResult runBakerUnder(const std::string& dir, const std::string& launcher, const std::string& args);
// `args` each quoted for the shell, joined.
std::string shellWords(const std::vector<std::string>& args);

}  // namespace baker::test
