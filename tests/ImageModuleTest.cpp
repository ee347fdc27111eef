// The image module (images/ImageFiles.h) as the baker executable meets it: loaded only by
// commands that need an image, and a clear failure, before any work or output, when it is
// missing or is not the module.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

class ImageModule : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* set = std::getenv("BAKER_IMAGE_MODULE")) saved_ = set;
    dir_ = test::makeTempDir("image-module");
    test::GltfBuilder plain;
    plain.node({{"mesh", plain.mesh({{"POSITION", plain.floats(test::triangleXY(), "VEC3")}})}});
    plain.write(dir_, "plain");

    test::GltfBuilder textured;
    const int texture = textured.texture(test::encodePng(1, 1, 3, {200, 100, 50}));
    const int material = textured.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
    textured.node({{"mesh", test::squareMesh(textured, 1.0f, material)}});
    textured.write(dir_, "textured");
  }
  void TearDown() override {
    if (saved_) {
      setenv("BAKER_IMAGE_MODULE", saved_->c_str(), 1);
    } else {
      unsetenv("BAKER_IMAGE_MODULE");
    }
  }

  // baker with the module looked for at `module` only (the child inherits the variable).
  test::ProcessResult runWithModule(const std::string& module, const std::string& args) {
    setenv("BAKER_IMAGE_MODULE", module.c_str(), 1);
    return test::runBaker(dir_, args);
  }
  bool exists(const std::string& name) const { return std::filesystem::exists(dir_ + "/" + name); }

  std::string dir_;
  std::optional<std::string> saved_;
};

TEST_F(ImageModule, IsNotNeededByABakeWithoutImages) {
  const test::ProcessResult run = runWithModule(dir_ + "/missing.so", "plain.gltf --sky 1,1,1 --rays 16 --out out.vdb");
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(exists("out.vdb"));
  const test::ProcessResult check = runWithModule(dir_ + "/missing.so", "validate out.vdb out.vdb --json");
  EXPECT_EQ(check.exitCode, 0) << check.err;
}

TEST_F(ImageModule, MissingItFailsATexturedSceneNamingWhereItLookedAndLeavesNoOutput) {
  const test::ProcessResult run = runWithModule(dir_ + "/missing.so", "textured.gltf --rays 16 --out out.vdb");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find("libbaker_images.so is missing (looked for " + dir_ + "/missing.so)"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("BAKER_IMAGE_MODULE"), std::string::npos) << run.err;
  EXPECT_FALSE(exists("out.vdb"));
}

TEST_F(ImageModule, MissingItFailsAnExrBakeBeforeBaking) {
  const test::ProcessResult run =
      runWithModule(dir_ + "/missing.so", "plain.gltf --sky 1,1,1 --rays 16 --format exr --out out.exr");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find("libbaker_images.so is missing"), std::string::npos) << run.err;
  // The bake prints its plan as it starts.
  EXPECT_EQ(run.err.find("plan:"), std::string::npos) << "failed only after starting the bake: " << run.err;
  EXPECT_FALSE(exists("out.exr"));
}

TEST_F(ImageModule, AFileThatIsNotAModuleIsRefused) {
  std::ofstream(dir_ + "/not_a_module.so") << "not a shared library\n";
  const test::ProcessResult run = runWithModule(dir_ + "/not_a_module.so", "textured.gltf --rays 16 --out out.vdb");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find(dir_ + "/not_a_module.so: cannot load baker's image module"), std::string::npos) << run.err;
  EXPECT_FALSE(exists("out.vdb"));
}

TEST_F(ImageModule, AModuleOfAnotherInterfaceOrWithoutTheEntryPointIsRefused) {
  const test::ProcessResult foreign = runWithModule(FOREIGN_IMAGE_MODULE, "textured.gltf --rays 16 --out out.vdb");
  EXPECT_EQ(foreign.exitCode, 1);
  EXPECT_NE(foreign.err.find("not the image module of this baker build (its interface differs)"), std::string::npos)
      << foreign.err;
  const test::ProcessResult entryless = runWithModule(ENTRYLESS_IMAGE_MODULE, "textured.gltf --rays 16 --out out.vdb");
  EXPECT_EQ(entryless.exitCode, 1);
  EXPECT_NE(entryless.err.find("(it has no baker_image_module_functions)"), std::string::npos) << entryless.err;
  EXPECT_FALSE(exists("out.vdb"));
}

TEST_F(ImageModule, TheBuiltOneServesTexturesAndExrVolumes) {
  // Found without the variable: beside the executable or in its build tree.
  unsetenv("BAKER_IMAGE_MODULE");
  const test::ProcessResult run = test::runBaker(dir_, "textured.gltf --sky 1,1,1 --rays 16 --format exr --out out.exr");
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err.find("use their factors instead"), std::string::npos) << "the texture was not decoded: " << run.err;
  EXPECT_TRUE(exists("out.exr/manifest.json"));
  const test::ProcessResult check = test::runBaker(dir_, "validate out.exr out.exr --json");
  EXPECT_EQ(check.exitCode, 0) << check.err;
}

}  // namespace
}  // namespace baker
