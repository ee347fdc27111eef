#pragma once
#include <CLI/CLI.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>

namespace baker {

// Runs one command's body and turns every failure into one line on stderr and an exit
// code: 2 for bad input (a file, a field, a flag), 1 for anything else. `body` parses and runs.
int runGuarded(const std::string& command, CLI::App& app, int argc, char** argv, const std::function<int()>& body);

// "x,y,z" → three finite numbers; InputError naming `flag` otherwise.
Eigen::Vector3d parseTriple(const std::string& flag, const std::string& text);

}  // namespace baker
