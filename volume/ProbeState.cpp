#include "volume/ProbeState.h"

namespace baker {

const char* probeStateName(ProbeState state) {
  switch (state) {
    case ProbeState::Valid: return "valid";
    case ProbeState::Relocated: return "relocated";
    case ProbeState::Invalid: return "invalid";
    case ProbeState::Interpolated: return "interpolated";
  }
  return "unknown";
}

}  // namespace baker
