#include "common/PeakMemory.h"

#include <sys/resource.h>

namespace baker {

std::uint64_t peakMemoryBytes() {
  struct rusage usage {};
  ::getrusage(RUSAGE_SELF, &usage);
  return std::uint64_t(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

}  // namespace baker
