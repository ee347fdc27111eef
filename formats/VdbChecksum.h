#pragma once
#include <cstdint>
#include <string>

namespace baker {

// OpenVDB parses what a file claims (sizes, offsets, node masks) without checking it against
// the file, so one flipped byte can crash it or make it allocate gigabytes. A baker .vdb
// therefore carries the XXH64 hash (seed 0) of its own bytes in the file metadata, and readers
// check it before OpenVDB sees the file.
//
// The hash is stored as 16 hex digits in the string metadata `kVdbChecksumKey`. It covers every
// byte of the file, with those 16 digits taken as '0' (their value while the writer hashes).
// Files of format 6 and older carry the 64-bit FNV-1a hash instead, under
// `kVdbLegacyChecksumKey`, covering the same bytes; both are read.
constexpr const char* kVdbChecksumKey = "baker.content_xxh64";
constexpr const char* kVdbLegacyChecksumKey = "baker.content_fnv1a64";
constexpr const char* kVdbChecksumPlaceholder = "0000000000000000";

// Replaces the placeholder the writer stored under kVdbChecksumKey in the first `headerBytes`
// bytes of the file at `path` (where the file's metadata ends) by the hash of the file. Throws
// std::runtime_error if the placeholder is not there exactly once.
void sealVdbChecksum(const std::string& path, std::uint64_t headerBytes);

// InputError naming `path` when the file has no checksum, more than one, or one that differs
// from its bytes (corrupted, truncated or edited). Reads the file in pieces: no allocation
// depends on what the file claims.
void requireVdbChecksum(const std::string& path);

}  // namespace baker
