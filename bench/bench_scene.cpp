// Scene loading and BVH build: time, triangles per second and peak memory.
//
//   bench_scene [SCENE.gltf|.glb] [--grid N] [--instances K] [--json]
//
// Without a scene it generates one: a wavy grid of N × N quads (2N² triangles, default N = 1024)
// placed by K nodes (default 1; K > 1 exercises instancing), written as .gltf + .bin in a
// temporary folder by a child process so that generating it does not count towards the peak.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/CommandLine.h"
#include "common/Error.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"

namespace {

double peakMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void writeGrid(const std::string& dir, int n, int instances) {
  const int side = n + 1;
  std::vector<float> positions;
  positions.reserve(std::size_t(side) * side * 3);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const float x = float(i) / n, z = float(j) / n;
      positions.insert(positions.end(), {x, 0.05f * std::sin(40.0f * x) * std::cos(37.0f * z), z});
    }
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(n) * n * 6);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = j * side + i, b = a + 1, c = a + side, d = c + 1;
      indices.insert(indices.end(), {a, c, b, b, c, d});
    }
  const std::size_t positionBytes = positions.size() * sizeof(float), indexBytes = indices.size() * sizeof(std::uint32_t);
  std::ofstream bin(dir + "/grid.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions.data()), positionBytes);
  bin.write(reinterpret_cast<const char*>(indices.data()), indexBytes);

  nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"buffers", {{{"uri", "grid.bin"}, {"byteLength", positionBytes + indexBytes}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteLength", positionBytes}},
        {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", indexBytes}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size() / 3}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
  };
  nlohmann::json nodes = nlohmann::json::array(), roots = nlohmann::json::array();
  for (int k = 0; k < instances; ++k) {
    nodes.push_back({{"mesh", 0}, {"translation", {1.1 * (k % 8), 0.3 * (k / 64), 1.1 * ((k / 8) % 8)}}});
    roots.push_back(k);
  }
  gltf["nodes"] = nodes;
  gltf["scenes"] = {{{"nodes", roots}}};
  std::ofstream(dir + "/grid.gltf") << gltf.dump();
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene;
  int grid = 1024, instances = 1;
  bool json = false;
  CLI::App app{"Scene loading and BVH build: time, triangles per second and peak memory."};
  app.add_option("scene", scene, "glTF scene (default: a generated wavy grid)")->check(CLI::ExistingFile);
  app.add_option("--grid", grid, "quads per side of the generated grid");
  app.add_option("--instances", instances, "nodes placing the generated grid");
  app.add_flag("--json", json, "print the results as JSON");
  return baker::runGuarded("bench_scene", app, argc, argv, [&] {
    // Bounded so that a typing slip cannot ask for more triangles than any machine holds.
    if (grid <= 0 || grid > 8192 || instances <= 0 || instances > 1024)
      throw baker::InputError(
          fmt::format("--grid must be in 1..8192 and --instances in 1..1024, got {} and {}", grid, instances));
    // The generated scene's folder goes whether the bench ends or fails.
    struct Folder {
      std::filesystem::path path;
      ~Folder() {
        std::error_code ignored;
        if (!path.empty()) std::filesystem::remove_all(path, ignored);
      }
    } generated;
    if (scene.empty()) {
      generated.path = std::filesystem::temp_directory_path() / ("bench-scene-" + std::to_string(getpid()));
      std::filesystem::create_directories(generated.path);
      const pid_t child = fork();
      if (child == 0) {
        writeGrid(generated.path.string(), grid, instances);
        _exit(0);
      }
      int status = 0;
      waitpid(child, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("generating the grid failed");
      scene = (generated.path / "grid.gltf").string();
    }

    const double before = peakMiB();
    auto start = std::chrono::steady_clock::now();
    const baker::Scene loaded = baker::loadGltf(scene);
    const double loadSeconds = secondsSince(start);
    const double afterLoad = peakMiB();
    start = std::chrono::steady_clock::now();
    const baker::RayTracer tracer(loaded);
    const double bvhSeconds = secondsSince(start);
    const double afterBvh = peakMiB();

    const double triangles = double(loaded.triangleCount());
    std::uint64_t unique = 0;
    for (const baker::Mesh& m : loaded.meshes) unique += m.triangleCount();
    if (json) {
      std::cout << nlohmann::json{{"scene", scene},
                                  {"world_triangles", std::uint64_t(triangles)},
                                  {"unique_triangles", unique},
                                  {"instances", loaded.instances.size()},
                                  {"instanced_meshes", tracer.instancedMeshes()},
                                  {"load_seconds", loadSeconds},
                                  {"bvh_seconds", bvhSeconds},
                                  {"peak_mib_before_load", before},
                                  {"peak_mib_after_load", afterLoad},
                                  {"peak_mib_after_bvh", afterBvh}}
                       .dump(2)
                << "\n";
      return 0;
    }
    std::cout << "scene          " << scene << "\n"
              << "triangles      " << std::uint64_t(triangles) << " in the world, " << unique << " unique, "
              << loaded.instances.size() << " instances, " << tracer.instancedMeshes() << " instanced meshes\n"
              << "load           " << loadSeconds << " s, " << unique / loadSeconds * 1e-6 << " M unique triangles/s\n"
              << "bvh            " << bvhSeconds << " s, " << unique / bvhSeconds * 1e-6 << " M unique triangles/s, "
              << triangles / bvhSeconds * 1e-6 << " M world triangles/s\n"
              << "peak memory    " << before << " MiB before loading, " << afterLoad << " MiB after loading, "
              << afterBvh << " MiB after the BVH\n";
    return 0;
  });
}
