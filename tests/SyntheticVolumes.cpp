#include "tests/SyntheticVolumes.h"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"

namespace baker::test {

void smoothProbe(const Basis& basis, const Eigen::Vector3d& x, float* coefficients, float* visibility) {
  for (int channel = 0; channel < 3; ++channel) {
    float* f = coefficients + basis.coefficientOffset(channel);
    f[0] = float(3.0 + 0.5 * channel + 0.3 * x.x() - 0.2 * x.z());  // the constant part
    f[1] = float(0.4 + 0.1 * x.y());                                // a lobe towards +Y
    for (int l = 2; l < 9; ++l) f[l] = float(0.02 * (l - 5) + 0.01 * x.x());
  }
  visibility[0] = float(1.5 + 0.1 * x.y());
  visibility[1] = 0.3f;
}

Volume smoothVolume(const Eigen::Vector3i& dims, const Eigen::Vector3d& origin, double spacing) {
  const auto basis = makeBasis("sh-l2");
  Volume v;
  v.grid.dims = dims;
  v.grid.origin = origin;
  v.grid.spacing = spacing;
  v.basisName = basis->name();
  v.coefficientsPerProbe = basis->totalCoefficients();
  v.visibilityPerProbe = basis->functions(0).count();
  const std::size_t n = std::size_t(v.grid.probeCount());
  v.coefficients.resize(n * v.coefficientsPerProbe);
  v.visibility.resize(n * v.visibilityPerProbe);
  v.states.assign(n, ProbeState::Valid);
  v.offsets.assign(n, Eigen::Vector3f::Zero());
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) {
        const std::int64_t p = v.grid.linearIndex(i, j, k);
        smoothProbe(*basis, v.grid.position(i, j, k), v.coefficients.data() + p * v.coefficientsPerProbe,
                    v.visibility.data() + p * v.visibilityPerProbe);
      }
  v.settings["rays"] = "64";
  return v;
}

void writeReferenceDirectory(const std::string& dir, const std::vector<Eigen::Vector3d>& positions,
                             const RgbImage& panorama, int bounces) {
  nlohmann::json probes = nlohmann::json::array();
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const std::string file = fmt::format("probe_{:04d}.exr", k);
    writeExr(panorama, dir + "/" + file);
    probes.push_back({{"index", k}, {"position_gltf", {positions[k].x(), positions[k].y(), positions[k].z()}},
                      {"file", file}});
  }
  const nlohmann::json manifest = {
      {"settings", {{"width", panorama.width}, {"height", panorama.height}, {"bounces", bounces}}},
      {"probes", probes}};
  std::ofstream(dir + "/probes.json") << manifest.dump(1);
}

RgbImage constantPanorama(int width, int height, const Eigen::Vector3f& radiance) {
  RgbImage image(width, height);
  for (std::size_t p = 0; p < std::size_t(width) * height; ++p)
    for (int c = 0; c < 3; ++c) image.pixels[3 * p + c] = radiance[c];
  return image;
}

}  // namespace baker::test
