#pragma once
#include <cstddef>
#include <cstdint>

namespace baker {

// 64-bit FNV-1a over bytes fed in any number of pieces: cheap, and enough to tell changed or
// corrupted bytes from the original (not a cryptographic digest: it does not resist forgery).
class Fnv1a64 {
 public:
  void add(const char* bytes, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) hash_ = (hash_ ^ std::uint8_t(bytes[i])) * 0x100000001b3ull;
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace baker
