#pragma once
#include <string>

namespace baker {

// Output that appears under its final name only when complete: writers fill temporaryPath()
// and call commit(); if they throw first, the destructor removes the temporary file, so a
// failed command never leaves a partial volume behind.
class AtomicFile {
 public:
  // Throws InputError if the directory of `finalPath` does not exist.
  explicit AtomicFile(std::string finalPath);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temporaryPath() const { return temporary_; }
  void commit();

 private:
  std::string final_;
  std::string temporary_;
  bool committed_ = false;
};

// A directory of output files that appears under its final name only when complete, the same
// way: writers fill temporaryPath() and call commit(). An existing directory at the final name
// is replaced only if `replaceable` says it is one of ours (InputError otherwise).
class AtomicDirectory {
 public:
  AtomicDirectory(std::string finalPath, bool (*replaceable)(const std::string& path));
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  const std::string& temporaryPath() const { return temporary_; }
  // Writes file `name` of the directory whole; InputError naming it when it cannot.
  void writeFile(const std::string& name, const std::string& bytes) const;
  void commit();

 private:
  std::string final_;
  std::string temporary_;
  bool committed_ = false;
};

// Whether `directory` holds a regular file `name`: how a directory of one of baker's formats is
// told from another (each has a file of its own name).
bool directoryHolds(const std::string& directory, const std::string& name);

// Throws InputError naming `path` if its directory does not exist; checked before baking so
// that a typo costs nothing.
void requireOutputDirectory(const std::string& path);

}  // namespace baker
