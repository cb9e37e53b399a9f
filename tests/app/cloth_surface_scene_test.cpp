// The render block's cloth aids (app/scene/cloth_surface_scene.h): subdivision, thickness and texture
// are read into RenderSettings::cloth_surface; a texture file is found relative to the scene
// file; bad values and a missing or unreadable image get an error naming the key and the file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "render/image.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

// A folder of its own under the build tree, emptied first.
std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(WEFT_BINARY_DIR) / "test_output" / "cloth_surface_scene" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ClothSurfaceScene, DefaultsLeaveTheClothAlone) {
  const Scene scene = test::parse_json_scene(test::scene_with_render(Json::object()));
  EXPECT_EQ(scene.render.cloth_surface.subdivision_levels, 0);
  EXPECT_EQ(scene.render.cloth_surface.thickness_m, 0.0);
  EXPECT_FALSE(scene.render.cloth_surface.texture.image);
}

TEST(ClothSurfaceScene, ReadsSubdivisionThicknessAndAWovenCheck) {
  const Scene scene = test::parse_json_scene(test::scene_with_render(Json::parse(R"({
    "subdivision": 2, "thickness": "3 mm",
    "texture": {"woven_check": {"stripes": 3, "warp": [1, 0, 0]}, "scale": ["20 cm", "10 cm"]}
  })")));
  const render::ClothSurface& c = scene.render.cloth_surface;
  EXPECT_EQ(c.subdivision_levels, 2);
  EXPECT_DOUBLE_EQ(c.thickness_m, 0.003);
  ASSERT_TRUE(c.texture.image);
  EXPECT_GT(c.texture.image->width(), 0);
  EXPECT_DOUBLE_EQ(c.texture.repeat_m.x(), 0.2);
  EXPECT_DOUBLE_EQ(c.texture.repeat_m.y(), 0.1);
}

// render.weave: off by default; true gives the built-in plain weave at its defaults; an object
// sets its repeat and depth; bad values name their key.
TEST(ClothSurfaceScene, ReadsTheWeaveAndTheSheen) {
  const auto surface = [](const char* render) {
    return test::parse_json_scene(test::scene_with_render(Json::parse(render))).render.cloth_surface;
  };
  EXPECT_FALSE(surface("{}").weave.normal_map);
  const render::ClothSurface on = surface(R"({"weave": true})");
  ASSERT_TRUE(on.weave.normal_map);
  EXPECT_EQ(on.weave.normal_map->width(), 64);
  EXPECT_DOUBLE_EQ(on.weave.repeat_m.x(), 0.002);
  EXPECT_DOUBLE_EQ(on.weave.depth, 0.5);
  const render::ClothSurface set = surface(
      R"({"weave": {"scale": ["3 mm", "1 mm"], "depth": 0.8}, "sheen": 0.2, "sheen_roughness": 0.7})");
  ASSERT_TRUE(set.weave.normal_map);
  EXPECT_DOUBLE_EQ(set.weave.repeat_m.x(), 0.003);
  EXPECT_DOUBLE_EQ(set.weave.repeat_m.y(), 0.001);
  EXPECT_DOUBLE_EQ(set.weave.depth, 0.8);
  EXPECT_DOUBLE_EQ(set.sheen, 0.2);
  EXPECT_DOUBLE_EQ(set.sheen_roughness, 0.7);
  EXPECT_FALSE(surface(R"({"weave": false})").weave.normal_map);

  const auto error_of = [](const char* render) {
    return test::scene_error_of(test::scene_with_render(Json::parse(render)));
  };
  EXPECT_CONTAINS(error_of(R"({"weave": {"depth": 1.5}})"), "render.weave.depth");
  EXPECT_CONTAINS(error_of(R"({"weave": {"scale": [0, 1]}})"), "render.weave.scale");
  EXPECT_CONTAINS(error_of(R"({"weave": {"file": "nowhere.png"}})"), "render.weave.file");
  EXPECT_CONTAINS(error_of(R"({"weave": {"threads": 4}})"), "render.weave.threads");
  EXPECT_CONTAINS(error_of(R"({"sheen": 2})"), "render.sheen");
}

TEST(ClothSurfaceScene, TextureFileIsRelativeToTheScene) {
  const std::filesystem::path dir = fresh_dir("relative");
  std::filesystem::create_directories(dir / "textures");
  render::write_png(render::Image(6, 4, {10, 20, 30}), dir / "textures" / "check.png");
  const Scene scene = parse_scene(
      test::scene_with_render(Json::parse(R"({"texture": {"file": "textures/check.png"}})")).dump(),
      (dir / "scene.json").string());
  ASSERT_TRUE(scene.render.cloth_surface.texture.image);
  EXPECT_EQ(scene.render.cloth_surface.texture.image->width(), 6);
  EXPECT_EQ(scene.render.cloth_surface.texture.image->height(), 4);
}

TEST(ClothSurfaceScene, BadTextureFileNamesKeyAndFile) {
  const std::filesystem::path dir = fresh_dir("bad");
  const std::filesystem::path source = dir / "scene.json";
  const std::string missing = test::scene_error_of(
      test::scene_with_render(Json::parse(R"({"texture": {"file": "nowhere.png"}})")), source);
  EXPECT_CONTAINS(missing, "render.texture.file");
  EXPECT_CONTAINS(missing, "nowhere.png");

  std::ofstream(dir / "not_an_image.png") << "this is text";
  const std::string garbage = test::scene_error_of(
      test::scene_with_render(Json::parse(R"({"texture": {"file": "not_an_image.png"}})")), source);
  EXPECT_CONTAINS(garbage, "render.texture.file");
  EXPECT_CONTAINS(garbage, "not_an_image.png");
}

TEST(ClothSurfaceScene, BadValuesNameTheirKey) {
  const auto error_of = [](const char* render) {
    return test::scene_error_of(test::scene_with_render(Json::parse(render)));
  };
  EXPECT_CONTAINS(error_of(R"({"subdivision": 4})"), "render.subdivision");
  EXPECT_CONTAINS(error_of(R"({"thickness": "-1 mm"})"), "render.thickness");
  EXPECT_CONTAINS(error_of(R"({"texture": {}})"), "exactly one of");
  EXPECT_CONTAINS(error_of(R"({"texture": {"file": "a.png", "woven_check": {}}})"),
                  "exactly one of");
  EXPECT_CONTAINS(error_of(R"({"texture": {"woven_check": {"stripes": 0}}})"),
                  "render.texture.woven_check.stripes");
  EXPECT_CONTAINS(error_of(R"({"texture": {"woven_check": {}, "scale": [0, 1]}})"),
                  "render.texture.scale");
  EXPECT_CONTAINS(error_of(R"({"texture": {"woven_check": {}, "colour": 1}})"),
                  "render.texture.colour");
  EXPECT_CONTAINS(error_of(R"({"texture": {"woven_check": {}, "mapping": "tile"}})"),
                  "render.texture.mapping");
  EXPECT_CONTAINS(error_of(R"({"texture": {"woven_check": {}, "mapping": "piece", "scale": [1, 1]}})"),
                  "render.texture.scale");
}

TEST(ClothSurfaceScene, ReadsThePieceMapping) {
  const Scene scene = test::parse_json_scene(
      test::scene_with_render(Json::parse(R"({"texture": {"woven_check": {}, "mapping": "piece"}})")));
  EXPECT_EQ(scene.render.cloth_surface.texture.mapping, render::TextureMapping::piece);
  EXPECT_NE(scene.render.cloth_surface.texture.image, nullptr);
}

// render.wireframe: off by default, true for the defaults, an object for
// width and colour; bad values name the key.
TEST(ClothSurfaceScene, ReadsTheWireframe) {
  const render::Wireframe defaults;
  EXPECT_FALSE(test::parse_json_scene(test::scene_with_render(Json::object()))
                   .render.cloth_surface.wireframe.enabled);
  const render::Wireframe on = test::parse_json_scene(test::scene_with_render(Json::parse(
                                   R"({"wireframe": true})"))).render.cloth_surface.wireframe;
  EXPECT_TRUE(on.enabled);
  EXPECT_EQ(on.width_px, defaults.width_px);
  EXPECT_EQ(on.color, defaults.color);
  EXPECT_FALSE(test::parse_json_scene(test::scene_with_render(Json::parse(
                   R"({"wireframe": false})"))).render.cloth_surface.wireframe.enabled);
  const render::Wireframe set = test::parse_json_scene(test::scene_with_render(Json::parse(
      R"({"wireframe": {"width": 2.5, "color": [1, 0.5, 0]}})"))).render.cloth_surface.wireframe;
  EXPECT_TRUE(set.enabled);
  EXPECT_EQ(set.width_px, 2.5);
  EXPECT_EQ(set.color, Eigen::Vector3f(1.0f, 0.5f, 0.0f));
}

TEST(ClothSurfaceScene, BadWireframeValuesNameTheirKey) {
  const auto error_of = [](const char* render) {
    return test::scene_error_of(test::scene_with_render(Json::parse(render)));
  };
  EXPECT_CONTAINS(error_of(R"({"wireframe": {"width": -1}})"), "render.wireframe.width");
  EXPECT_CONTAINS(error_of(R"({"wireframe": {"width": 0}})"), "render.wireframe.width");
  EXPECT_CONTAINS(error_of(R"({"wireframe": {"width": 100}})"), "render.wireframe.width");
  EXPECT_CONTAINS(error_of(R"({"wireframe": {"color": [1, 0]}})"), "render.wireframe.color");
  EXPECT_CONTAINS(error_of(R"({"wireframe": {"color": [1, 0, 2]}})"), "render.wireframe.color");
  EXPECT_CONTAINS(error_of(R"({"wireframe": {"colour": [1, 0, 0]}})"), "render.wireframe.colour");
  EXPECT_CONTAINS(error_of(R"({"wireframe": "thick"})"), "render.wireframe");
}

}  // namespace
}  // namespace weft::app
