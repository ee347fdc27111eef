#pragma once
#include <algorithm>
#include <stdexcept>
#include <string>

namespace baker {

// Something the user gave us is wrong (a file, a field, a flag). The message names what
// and where; the command line turns it into exit code 2 and leaves no output behind.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// The maths refused (for example a numerically singular Gram matrix). Not the user's
// input as such, but still reported as one line rather than a crash.
class NumericalError : public std::runtime_error {
 public:
  explicit NumericalError(const std::string& message) : std::runtime_error(message) {}
};

// Library messages (tinygltf, OpenImageIO) may span lines; every error baker prints is one.
inline std::string oneLine(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message.empty() ? "unknown error" : message;
}

}  // namespace baker
