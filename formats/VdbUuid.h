#pragma once
#include <string>

namespace baker {

// OpenVDB writes a random UUID into every file header (Archive::writeHeader), so two writes of
// one volume would differ in 36 bytes and "the same inputs give the same file" could not hold.
// A baker .vdb carries instead a UUID derived from the file's other bytes: identical volumes are
// identical files, and different ones still get different tags (an RFC 9562 version-8 UUID from
// two XXH64 hashes, seeds 1 and 2, of the file with the UUID's bytes read as '0'; files of format
// 6 and older took two FNV-1a hashes).
//
// Replaces the UUID in the header of the just-written file at `path`; to be called before
// sealVdbChecksum, whose hash covers it. Throws std::runtime_error if the header does not hold a
// UUID where OpenVDB puts one.
void deriveVdbUuid(const std::string& path);

}  // namespace baker
