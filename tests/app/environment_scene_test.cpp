// The render block's image-based lighting (app/scene/environment_scene.h): render.environment is read
// into RenderSettings::environment with its map found relative to the scene file; bad values
// and a missing or unreadable map get an error naming the key and the file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "render/environment.h"
#include "render/image.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

// A folder of its own under the build tree, emptied first, holding maps/sky.hdr (8×4).
std::filesystem::path folder_with_map(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(WEFT_BINARY_DIR) / "test_output" / "environment_scene" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "maps");
  render::write_environment_map(
      dir / "maps" / "sky.hdr",
      render::EnvironmentMap(8, 4, std::vector<Eigen::Vector3f>(32, Eigen::Vector3f(1, 2, 3))));
  return dir;
}

TEST(EnvironmentScene, NoEnvironmentByDefault) {
  const Scene scene = test::parse_json_scene(test::scene_with_render(Json::object()));
  EXPECT_FALSE(scene.render.environment.map);
}

TEST(EnvironmentScene, MapIsRelativeToTheSceneWithItsSettings) {
  const std::filesystem::path dir = folder_with_map("relative");
  const Scene scene = parse_scene(
      test::scene_with_render(Json::parse(R"({"environment": {"file": "maps/sky.hdr",
          "rotation": "0.5 rad", "intensity": 2.5, "background": false}})"))
          .dump(),
      (dir / "scene.json").string());
  const render::Environment& e = scene.render.environment;
  ASSERT_TRUE(e.map);
  EXPECT_EQ(e.map->width(), 8);
  EXPECT_EQ(e.map->height(), 4);
  EXPECT_NEAR(e.map->texel(3, 2).y(), 2.0f, 0.02f);
  EXPECT_NEAR(e.rotation_deg, 0.5 * 180.0 / 3.14159265358979, 1e-9);
  EXPECT_DOUBLE_EQ(e.intensity, 2.5);
  EXPECT_FALSE(e.background);
}

// stb reads a PNG as floats whatever its name: a PNG named .hdr used to light the scene with
// made-up radiance; a device used to be read on and on.
TEST(EnvironmentScene, APngNamedHdrOrADeviceIsNotAnEnvironmentMap) {
  const std::filesystem::path dir = folder_with_map("png");
  render::write_png(render::Image(8, 4, {200, 200, 200}), dir / "maps" / "fake.hdr");
  const std::string png = test::scene_error_of(
      test::scene_with_render(Json::parse(R"({"environment": {"file": "maps/fake.hdr"}})")),
      dir / "scene.json");
  EXPECT_CONTAINS(png, "render.environment.file");
  EXPECT_CONTAINS(png, "fake.hdr': not a Radiance .hdr file");
  const std::string device = test::scene_error_of(
      test::scene_with_render(Json::parse(R"({"environment": {"file": "/dev/zero"}})")),
      dir / "scene.json");
  EXPECT_CONTAINS(device, "/dev/zero: cannot read an image file (not a regular file");
}

TEST(EnvironmentScene, BadMapOrValuesNameTheKeyAndFile) {
  const std::filesystem::path dir = folder_with_map("bad");
  const std::filesystem::path source = dir / "scene.json";
  const auto error_of = [&](const char* render) {
    return test::scene_error_of(test::scene_with_render(Json::parse(render)), source);
  };
  const std::string missing = error_of(R"({"environment": {"file": "nowhere.hdr"}})");
  EXPECT_CONTAINS(missing, "render.environment.file");
  EXPECT_CONTAINS(missing, "nowhere.hdr");
  std::ofstream(dir / "text.hdr") << "this is text";
  const std::string garbage = error_of(R"({"environment": {"file": "text.hdr"}})");
  EXPECT_CONTAINS(garbage, "render.environment.file");
  EXPECT_CONTAINS(garbage, "text.hdr");
  EXPECT_CONTAINS(error_of(R"({"environment": {"rotation": 10}})"), "render.environment.file");
  EXPECT_CONTAINS(error_of(R"({"environment": {"file": "maps/sky.hdr", "intensity": -1}})"),
                  "render.environment.intensity");
  EXPECT_CONTAINS(error_of(R"({"environment": {"file": "maps/sky.hdr", "exposure": 1}})"),
                  "render.environment.exposure");
}

}  // namespace
}  // namespace weft::app
