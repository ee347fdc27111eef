#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "common/Xxh64.h"

namespace baker {
namespace {

// Bytes (31 i + 7) mod 256: no run repeats within a stripe, so a lane or a tail read from the
// wrong place changes the hash.
std::string pattern(std::size_t length) {
  std::string bytes(length, '\0');
  for (std::size_t i = 0; i < length; ++i) bytes[i] = char((i * 31 + 7) & 0xff);
  return bytes;
}

// Expected values printed by `xxhsum -H1` (xxHash 0.8.1, Debian's package), an implementation this
// project did not write: every path of the hash (no stripe, a tail of 8, 4 and single bytes, one
// stripe and more) is covered by these lengths.
TEST(Xxh64, MatchesXxhsumOnEveryPathThroughTheHash) {
  const std::pair<std::size_t, std::uint64_t> expected[] = {
      {0, 0xef46db3751d8e999ull},   {1, 0xa96c7f0ce858bbb7ull},  {4, 0xc60d15b1e3ff8f04ull},
      {8, 0x3da5c7aa269683e0ull},   {31, 0x4a74f3a1a39ad4a1ull}, {32, 0x8d57d6a4671cc43dull},
      {33, 0x62c9fd21ed857664ull},  {100, 0xefa0ad2d3e70c151ull}, {1000, 0x99594f4828043d35ull}};
  for (const auto& [length, value] : expected) {
    const std::string bytes = pattern(length);
    Xxh64 whole;
    whole.add(bytes.data(), bytes.size());
    EXPECT_EQ(whole.value(), value) << length << " bytes at once";
  }
}

// A file is hashed in pieces of whatever size its reader returns: any cut gives the same value.
TEST(Xxh64, PiecesOfAnySizeGiveTheWholeInputsHash) {
  const std::string bytes = pattern(1000);
  for (std::size_t piece : {1, 3, 7, 31, 33, 64, 999}) {
    Xxh64 inPieces;
    for (std::size_t at = 0; at < bytes.size(); at += piece)
      inPieces.add(bytes.data() + at, std::min(piece, bytes.size() - at));
    EXPECT_EQ(inPieces.value(), 0x99594f4828043d35ull) << "pieces of " << piece;
  }
}

TEST(Xxh64, TheSeedChangesTheHash) {
  const std::string bytes = pattern(100);
  Xxh64 zero(0), one(1), two(2);
  for (Xxh64* h : {&zero, &one, &two}) h->add(bytes.data(), bytes.size());
  EXPECT_EQ(zero.value(), 0xefa0ad2d3e70c151ull);
  EXPECT_NE(one.value(), zero.value());
  EXPECT_NE(two.value(), one.value());
}

}  // namespace
}  // namespace baker
