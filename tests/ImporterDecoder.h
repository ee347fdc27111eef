#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "basis/Basis.h"
#include "basis/StoredSignal.h"
#include "decoders/baker_irradiance.h"
#include "formats/ReconstructionData.h"

namespace baker::test {

// The header decoder as an importer builds it from a file's "baker.reconstruction": the basis
// name, sg-N's sharpness, the file's lobe axes, and for radiance the diffuse response series.
inline baker_decode::BasisDecoder importerDecoder(const Basis& basis, StoredSignal signal) {
  const nlohmann::json set = reconstructionData(basis, signal)["function_sets"][0];
  const bool gaussians = set["type"] == "spherical-gaussians";
  baker_decode::BasisDecoder decoder(basis.name().c_str(), gaussians ? set["sharpness"].get<double>() : 0.0);
  if (set.contains("axes")) {
    std::vector<double> axes;
    for (const nlohmann::json& axis : set["axes"])
      for (int k = 0; k < 3; ++k) axes.push_back(axis[k].get<double>());
    decoder.setLobeAxes(axes.data());
  }
  if (set.contains("diffuse_response") && set["diffuse_response"].is_object() &&
      set["diffuse_response"]["type"] == "legendre") {
    const std::vector<double> series = set["diffuse_response"]["coefficients"].get<std::vector<double>>();
    decoder.setDiffuseResponse(series.data(), int(series.size()));
  }
  return decoder;
}

}  // namespace baker::test
