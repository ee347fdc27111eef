#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <istream>
#include <vector>

namespace baker {

// Feeds `consume(bytes, count)` the stream's bytes from its start, piece by piece, with the
// `length` bytes at offset `from` read as '0': what a hash of a file covers when the file holds a
// field the hash goes into (its checksum, its UUID).
template <typename Consume>
void readWithZeroedField(std::istream& in, std::uint64_t from, std::uint64_t length, Consume consume) {
  in.clear();
  in.seekg(0);
  std::vector<char> piece(1 << 16);
  for (std::uint64_t position = 0; in;) {
    in.read(piece.data(), std::streamsize(piece.size()));
    const std::size_t count = std::size_t(in.gcount());
    const std::uint64_t first = std::max(from, position), end = std::min(from + length, position + count);
    if (first < end)
      std::fill(piece.begin() + std::ptrdiff_t(first - position), piece.begin() + std::ptrdiff_t(end - position), '0');
    consume(piece.data(), count);
    position += count;
  }
}

}  // namespace baker
