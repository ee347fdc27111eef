#pragma once
#include <string>

namespace baker {

// A 64-bit FNV-1a hash of a file's bytes, as 16 hex digits: enough to tell a changed scene
// from an unchanged one (not a cryptographic digest). InputError naming the file if unreadable.
std::string fileHash(const std::string& path);

}  // namespace baker
