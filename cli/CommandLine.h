#pragma once
#include <CLI/CLI.hpp>

#include <Eigen/Core>

#include <exception>
#include <functional>
#include <string>

#include "common/Error.h"

namespace baker {

// Runs one command's body and turns every failure into one line on stderr and an exit
// code: 2 for bad input (a file, a field, a flag), 1 for anything else. `body` parses and runs.
int runGuarded(const std::string& command, CLI::App& app, int argc, char** argv, const std::function<int()>& body);

// What runGuarded does with an exception thrown by a command's body: one line on stderr, and the
// exit code (2 for bad input, 1 for anything else). For bodies that must act on the code (an
// MPI rank stops the job with it).
int reportFailure(const std::string& command, std::exception_ptr failure);

// The flag that sets a library setting (SettingError::setting): "sg_sharpness" → "--sg-sharpness".
std::string flagOf(const std::string& setting);
// The error as the command line says it: a setting's problem after its flag.
std::string commandLineMessage(const InputError& error);

// "x,y,z" → three finite numbers; InputError naming `flag` otherwise.
Eigen::Vector3d parseTriple(const std::string& flag, const std::string& text);
// "x,y,z" → that direction, normalised; InputError naming `flag` also for the zero vector.
Eigen::Vector3d parseDirection(const std::string& flag, const std::string& text);

}  // namespace baker
