#pragma once
#include <nlohmann/json.hpp>

#include "basis/Basis.h"
#include "basis/StoredSignal.h"

namespace baker {

// Everything an importer needs to evaluate a volume's coefficients without re-deriving the
// basis: family, colour space and its conversion to RGB, per channel the coefficient count,
// offset and function set, and each function set's constants (SH order and convention,
// icosahedron vertices and tangent frames, lobe axes and sharpness, ...). Files store its
// dump() under "baker.reconstruction"; docs/DECODERS.md gives the formulas it refers to.
// "signal" says what the coefficients hold, so that a decoder which evaluates the stored
// function as irradiance can refuse radiance coefficients instead of misreading them.
nlohmann::json reconstructionData(const Basis& basis, StoredSignal signal);

}  // namespace baker
