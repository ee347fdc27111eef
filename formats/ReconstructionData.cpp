#include "formats/ReconstructionData.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "bake/AmbientCubeBasis.h"
#include "bake/AmbientDiceBezier.h"
#include "bake/AmbientDiceLinear.h"
#include "bake/AmbientDiceSrbf.h"
#include "bake/Icosahedron.h"
#include "bake/SphericalGaussianBasis.h"
#include "bake/SphericalHarmonics.h"

namespace baker {
namespace {

using nlohmann::json;

// Adding 0 turns −0 into 0, which some readers print oddly.
json direction(const Eigen::Vector3d& d) { return json::array({d.x() + 0.0, d.y() + 0.0, d.z() + 0.0}); }

const char* barycentricsName(Barycentrics kind) { return kind == Barycentrics::Spherical ? "spherical" : "flat"; }

// The angle θ between neighbouring icosahedron vertices enters the Bézier derivative units.
double halfEdgeCosine() {
  const Icosahedron& ico = Icosahedron::instance();
  const std::array<int, 3>& corners = ico.triangle(0);
  return std::sqrt(0.5 * (1.0 + ico.vertex(corners[0]).dot(ico.vertex(corners[1]))));
}

// One function set, with the constants its formula in docs/DECODERS.md needs; the icosahedron's
// vertices and frames are shared by the Ambient Dice sets and listed once, at the top level.
json functionSetData(const SphericalFunctions& functions) {
  json set = {{"count", functions.count()}};
  if (const auto* sh = dynamic_cast<const SphericalHarmonics*>(&functions)) {
    set["type"] = "sh";
    set["order"] = sh->order();
    set["convention"] =
        "real, orthonormal (integral of Y_i Y_j over the sphere = delta_ij), polar axis z, no Condon-Shortley phase; "
        "index l*l+l+m; m>0 ~ cos(m phi), m<0 ~ sin(|m| phi), phi = atan2(y, x); "
        "Y(1,-1) = c y, Y(1,0) = c z, Y(1,1) = c x with c = sqrt(3/(4 pi))";
  } else if (const auto* linear = dynamic_cast<const AmbientDiceLinearFunctions*>(&functions)) {
    set["type"] = "icosahedron-linear";
    set["barycentrics"] = barycentricsName(linear->barycentrics());
    set["per_vertex"] = json::array({"value"});
    set["interpolation"] = "sum over the corners k of the triangle containing n of b_k value[vertex_k]";
  } else if (const auto* lobes = dynamic_cast<const AmbientDiceSrbfFunctions*>(&functions)) {
    set["type"] = "icosahedron-lobes";
    set["per_vertex"] = json::array({"lobe weight"});
    set["lobe"] = "f_i(n) = cos2 c^2 + cos4 c^4, c = max(0, vertices[i].n)";
    set["cos2"] = lobes->cos2Coefficient();
    set["cos4"] = lobes->cos4Coefficient();
  } else if (const auto* bezier = dynamic_cast<const AmbientDiceBezierFunctions*>(&functions)) {
    set["type"] = "icosahedron-bezier";
    set["barycentrics"] = barycentricsName(bezier->barycentrics());
    set["per_vertex"] = json::array({"value", "d_tangent", "d_bitangent"});
    set["patch"] = "hybrid cubic Bezier triangle of Ambient Dice (Iwanicki and Sloan 2017, 2.3.1): docs/DECODERS.md";
    set["index"] = "3 vertex + datum";
    set["vertex_factor"] = bezier->vertexFactor();
    set["interior"] = bezier->interiorWeights();
    set["alpha"] = AmbientDiceBezierFunctions::alpha();
    set["stored_gradient_scale"] = halfEdgeCosine();
    set["derivatives"] =
        "(d_tangent, d_bitangent) = stored_gradient_scale times the patch's gradient on the sphere at the vertex, "
        "in the vertex's (tangent, bitangent) frame";
  } else if (dynamic_cast<const AmbientCubeLobes*>(&functions)) {
    set["type"] = "cube-lobes";
    set["axes"] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    set["lobe"] = "f_i(n) = max(0, axes[i].n)^2";
  } else if (const auto* gaussians = dynamic_cast<const SphericalGaussians*>(&functions)) {
    set["type"] = "spherical-gaussians";
    set["sharpness"] = gaussians->sharpness();
    set["lobe"] = "f_i(n) = exp(sharpness (axes[i].n - 1))";
    set["axes_rule"] = "spherical Fibonacci: z = 1 - (2i+1)/count, phi = i pi (3 - sqrt 5), r = sqrt(1 - z^2)";
    json axes = json::array();
    for (const Eigen::Vector3d& axis : gaussians->axes()) axes.push_back(direction(axis));
    set["axes"] = axes;
  } else {
    // A new function set must be described here before volumes using it can be written.
    throw std::logic_error("reconstructionData: undescribed function set");
  }
  return set;
}

const char* familyName(const json& firstSet) {
  const std::string type = firstSet["type"];
  if (type == "sh") return "sh";
  if (type == "cube-lobes") return "ambient-cube";
  if (type == "spherical-gaussians") return "spherical-gaussians";
  return "ambient-dice";
}

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

json reconstructionData(const Basis& basis) {
  std::vector<const SphericalFunctions*> distinct;
  json sets = json::array(), channels = json::array();
  for (int c = 0; c < 3; ++c) {
    const SphericalFunctions* functions = &basis.functions(c);
    std::size_t index = 0;
    while (index < distinct.size() && distinct[index] != functions) ++index;
    if (index == distinct.size()) {
      distinct.push_back(functions);
      sets.push_back(functionSetData(*functions));
    }
    channels.push_back({{"name", channelName(basis.colorSpace(), c)},
                        {"offset", basis.coefficientOffset(c)},
                        {"count", basis.coefficientCount(c)},
                        {"functions", index}});
  }

  json data = {{"family", familyName(sets[0])}, {"variant", basis.name()}, {"color_space", colorSpaceName(basis.colorSpace())}};
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
  data["value"] = "channel c at unit normal n: sum over i of coefficients[offset_c + i] f_i(n), f = function_sets[functions_c]";
  data["visibility"] = "sum over i of visibility[i] f_i(n), f = channel 0's function set";
  data["function_sets"] = sets;
  if (data["family"] == "ambient-dice") {
    bool bezier = false;
    for (const json& set : sets) bezier = bezier || set["type"] == "icosahedron-bezier";
    data["icosahedron"] = icosahedronData(bezier);
  }
  return data;
}

}  // namespace baker
