#pragma once
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace baker {

// Something the user gave us is wrong (a file, a field, a flag). The message names what
// and where; the command line turns it into exit code 2 and leaves no output behind.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A request's setting has a value the library refuses. `setting` is the request's own name for
// it (e.g. "spacing", "env_intensity"); `problem` reads after that name ("must be positive, got
// -1"). A front end names the setting its own way: the command line prints its flag.
class SettingError : public InputError {
 public:
  SettingError(std::string setting, std::string problem)
      : InputError(setting + " " + problem), setting_(std::move(setting)), problem_(std::move(problem)) {}
  const std::string& setting() const { return setting_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string setting_, problem_;
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
