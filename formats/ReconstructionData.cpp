#include "formats/ReconstructionData.h"

#include <cmath>
#include <vector>

#include "basis/DiffuseResponse.h"
#include "basis/Icosahedron.h"

namespace baker {
namespace {

using nlohmann::json;

// Adding 0 turns −0 into 0, which some readers print oddly.
json direction(const Eigen::Vector3d& d) { return json::array({d.x() + 0.0, d.y() + 0.0, d.z() + 0.0}); }

json icosahedronData(bool withTangentFrames) {
  const Icosahedron& ico = Icosahedron::instance();
  json vertices = json::array(), tangents = json::array(), bitangents = json::array();
  for (int i = 0; i < Icosahedron::kVertexCount; ++i) {
    vertices.push_back(direction(ico.vertex(i)));
    tangents.push_back(direction(ico.tangent(i)));
    bitangents.push_back(direction(ico.bitangent(i)));
  }
  json triangles = json::array();
  for (int t = 0; t < Icosahedron::kTriangleCount; ++t) triangles.push_back(ico.triangle(t));
  json data = {{"vertices", vertices},
               {"triangles", triangles},
               {"barycentrics",
                "spherical b = [v0 v1 v2]^-1 n, n in the triangle whose b are all >= 0; flat: b / (b0 + b1 + b2)"}};
  if (withTangentFrames) {
    data["tangents"] = tangents;
    data["bitangents"] = bitangents;
  }
  return data;
}

}  // namespace

json reconstructionData(const Basis& basis, StoredSignal signal) {
  std::vector<const SphericalFunctions*> distinct;
  json sets = json::array(), channels = json::array();
  for (int c = 0; c < 3; ++c) {
    const SphericalFunctions* functions = &basis.functions(c);
    std::size_t index = 0;
    while (index < distinct.size() && distinct[index] != functions) ++index;
    if (index == distinct.size()) {
      distinct.push_back(functions);
      json set = functions->describe();
      set["count"] = functions->count();
      if (signal == StoredSignal::Radiance) set["diffuse_response"] = diffuseResponseOf(basis, c)->describe();
      sets.push_back(set);
    }
    channels.push_back({{"name", channelName(basis.colorSpace(), c)},
                        {"offset", basis.coefficientOffset(c)},
                        {"count", basis.coefficientCount(c)},
                        {"functions", index}});
  }

  json data = {{"family", basis.family()}, {"variant", basis.name()}, {"color_space", colorSpaceName(basis.colorSpace())}};
  if (basis.colorSpace() != ColorSpace::Rgb) {
    json rows = json::array();
    for (int row = 0; row < 3; ++row) {
      json entries = json::array();
      for (int column = 0; column < 3; ++column)
        entries.push_back(toRgb(basis.colorSpace(), Eigen::Vector3f::Unit(column))[row]);
      rows.push_back(entries);
    }
    data["to_rgb"] = rows;
  }
  data["channels"] = channels;
  data["signal"] = storedSignalName(signal);
  if (signal == StoredSignal::Radiance) {
    data["value"] =
        "channel c: radiance L(w) = sum over i of coefficients[offset_c + i] f_i(w), f = function_sets[functions_c]; "
        "irradiance E(n) = sum over i of coefficients[offset_c + i] K_i(n), K_i(n) = integral of f_i(w) max(0, n.w) dw";
    data["visibility"] = "V(w) = sum over i of visibility[i] f_i(w), f = channel 0's function set";
  } else {
    data["value"] =
        "channel c at unit normal n: sum over i of coefficients[offset_c + i] f_i(n), f = function_sets[functions_c]";
    data["visibility"] = "sum over i of visibility[i] f_i(n), f = channel 0's function set";
  }
  data["function_sets"] = sets;
  // Every Ambient Dice basis lists the icosahedron (ad-hemi9's axes_rule turns it).
  if (data["family"] == "ambient-dice") {
    bool bezier = false;
    for (const json& set : sets) bezier = bezier || set["type"] == "icosahedron-bezier";
    data["icosahedron"] = icosahedronData(bezier);
  }
  return data;
}

}  // namespace baker
