#include "cli/CommandLine.h"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <sstream>

#include "common/Error.h"

namespace baker {

std::string flagOf(const std::string& setting) {
  if (setting == "turned_off") return "--no";
  std::string flag = "--" + setting;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string commandLineMessage(const InputError& error) {
  const auto* setting = dynamic_cast<const SettingError*>(&error);
  if (!setting) return error.what();
  const std::string& problem = setting->problem();
  return flagOf(setting->setting()) + (problem.rfind(":", 0) == 0 ? "" : " ") + problem;
}

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
  } catch (...) {
    return reportFailure(command, std::current_exception());
  }
}

int reportFailure(const std::string& command, std::exception_ptr failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const InputError& e) {
    std::cerr << fmt::format("{}: error: {}\n", command, commandLineMessage(e));
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << fmt::format("{}: error: {}\n", command, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::cerr << fmt::format("{}: failed: {}\n", command, e.what());
    return 1;
  }
}

Eigen::Vector3d parseTriple(const std::string& flag, const std::string& text) {
  std::istringstream in(text);
  Eigen::Vector3d v;
  char comma1 = 0, comma2 = 0;
  if (!(in >> v.x() >> comma1 >> v.y() >> comma2 >> v.z()) || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof() ||
      !v.allFinite())
    throw InputError(fmt::format("{} {}: expected three finite numbers x,y,z", flag, text));
  return v;
}

Eigen::Vector3d parseDirection(const std::string& flag, const std::string& text) {
  const Eigen::Vector3d v = parseTriple(flag, text);
  if (!(v.norm() > 0.0)) throw InputError(flag + " must not be zero");
  return v.normalized();
}

}  // namespace baker
