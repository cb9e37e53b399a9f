// The render block's "gl" key: which OpenGL context the rasterizer gets (render/gl_context.h),
// "auto" by default; an unknown value is an error naming the key and listing the choices.

#include <gtest/gtest.h>

#include <string>

#include "app/json_reader.h"
#include "app/scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json scene_with_render(const Json& render) {
  Json s = Json::parse(R"({
    "description": "test scene",
    "cloth": {"size": ["1 m", "1 m"], "resolution": [5, 5]},
    "output": {"fps": 24, "frames": 2}
  })");
  s["render"] = render;
  return s;
}

TEST(GlScene, DefaultIsAuto) {
  EXPECT_EQ(test::parse_json_scene(scene_with_render(Json::object())).render.gl,
            render::GlBackend::automatic);
}

TEST(GlScene, ReadsEachChoice) {
  for (const char* name : {"auto", "osmesa", "egl"}) {
    const Scene s = test::parse_json_scene(scene_with_render(Json{{"gl", name}}));
    EXPECT_STREQ(render::gl_backend_name(s.render.gl), name);
  }
}

TEST(GlScene, UnknownValueNamesTheKeyAndTheChoices) {
  const std::string error = test::scene_error_of(scene_with_render(Json{{"gl", "vulkan"}}));
  EXPECT_NE(error.find("render.gl"), std::string::npos) << error;
  EXPECT_NE(error.find("egl"), std::string::npos) << error;
  EXPECT_NE(error.find("osmesa"), std::string::npos) << error;
}

}  // namespace
}  // namespace weft::app
