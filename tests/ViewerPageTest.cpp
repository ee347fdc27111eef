#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/Error.h"
#include "tests/TestData.h"
#include "viewer/SceneCopy.h"
#include "viewer/ViewerPage.h"

// What baker view copies and finds: a scene's own files and nothing else; the scene beside a volume.
namespace baker {
namespace {

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

TEST(SceneCopy, CopiesTheFilesOfTheSceneFolderAtTheirRelativePaths) {
  const std::filesystem::path dir = test::makeTempDir("scene_copy");
  writeText(dir / "in/sub/mesh data.bin", "0123");
  writeText(dir / "in/room.gltf",
            R"({"asset":{"version":"2.0"},"buffers":[{"uri":"sub/mesh%20data.bin","byteLength":4},)"
            R"({"uri":"data:application/octet-stream;base64,AAAA","byteLength":3}],"images":[{"uri":"missing.png"}]})");
  EXPECT_EQ(copyScene((dir / "in/room.gltf").string(), (dir / "out/scene").string()), "scene/room.gltf");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out/scene/room.gltf"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out/scene/sub/mesh data.bin"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out/scene/missing.png"));  // missing for the bake too
}

TEST(SceneCopy, RefusesReferencesOutsideTheSceneFolder) {
  const std::filesystem::path dir = test::makeTempDir("scene_copy_outside");
  writeText(dir / "secret.bin", "secret");
  for (const char* uri : {"../secret.bin", "/etc/hostname", "file:///etc/hostname"}) {
    writeText(dir / "in/room.gltf", std::string(R"({"asset":{"version":"2.0"},"buffers":[{"uri":")") + uri +
                                        R"(","byteLength":6}]})");
    try {
      copyScene((dir / "in/room.gltf").string(), (dir / "out").string());
      ADD_FAILURE() << uri << " was copied";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("buffers[0].uri"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out/secret.bin"));
  }
}

TEST(ViewerPage, FindsTheSceneBesideTheVolumeWhateverThePathLooksLike) {
  const std::filesystem::path dir = test::makeTempDir("viewer_scene");
  writeText(dir / "room.gltf", "{}");
  writeText(dir / "room_exr/manifest.json", "{}");
  Volume volume;
  volume.settings["scene"] = "room.gltf";
  for (const std::string& path : {(dir / "room_exr").string(), (dir / "room_exr/").string(), (dir / "room_exr/manifest.json").string()})
    EXPECT_EQ(std::filesystem::path(sceneOfVolume(volume, path, "")), dir / "room.gltf") << path;
  volume.settings["scene"] = "elsewhere.gltf";
  EXPECT_EQ(sceneOfVolume(volume, (dir / "room_exr").string(), ""), "");
  EXPECT_THROW(sceneOfVolume(volume, (dir / "room_exr").string(), (dir / "no.gltf").string()), InputError);
}

}  // namespace
}  // namespace baker
