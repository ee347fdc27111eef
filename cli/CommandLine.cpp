#include "cli/CommandLine.h"

#include <fmt/format.h>

#include <iostream>

#include "common/Error.h"

namespace baker {

int runGuarded(const std::string& command, CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::cout << BAKER_VERSION << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << fmt::format("{}: error: {}\n", command, e.what());
    return 2;
  }
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << fmt::format("{}: error: {}\n", command, e.what());
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << fmt::format("{}: error: {}\n", command, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::cerr << fmt::format("{}: failed: {}\n", command, e.what());
    return 1;
  }
}

}  // namespace baker
