// The render block's "gl" key: which OpenGL context the rasterizer gets (render/gl_context.h),
// "auto" by default; an unknown value is an error naming the key and listing the choices. And
// the environment variable WEFT_GL, which app/ (app/run/renderer_choice.h) lets override it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/scene/json_reader.h"
#include "app/run/renderer_choice.h"
#include "app/scene/scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

// Sets an environment variable for one scope and restores the previous value.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : m_name(name) {
    if (const char* old = std::getenv(name)) m_old = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnvironment() {
    if (m_old)
      ::setenv(m_name.c_str(), m_old->c_str(), 1);
    else
      ::unsetenv(m_name.c_str());
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  std::string m_name;
  std::optional<std::string> m_old;
};

TEST(GlScene, DefaultIsAuto) {
  EXPECT_EQ(test::parse_json_scene(test::scene_with_render(Json::object())).render.gl,
            render::GlBackend::automatic);
}

TEST(GlScene, ReadsEachChoice) {
  for (const char* name : {"auto", "osmesa", "egl"}) {
    const Scene s = test::parse_json_scene(test::scene_with_render(Json{{"gl", name}}));
    EXPECT_STREQ(render::gl_backend_name(s.render.gl), name);
  }
}

TEST(GlScene, UnknownValueNamesTheKeyAndTheChoices) {
  const std::string error = test::scene_error_of(test::scene_with_render(Json{{"gl", "vulkan"}}));
  EXPECT_NE(error.find("render.gl"), std::string::npos) << error;
  EXPECT_NE(error.find("egl"), std::string::npos) << error;
  EXPECT_NE(error.find("osmesa"), std::string::npos) << error;
}

TEST(GlEnvironment, UnsetOrEmptyKeepsTheScenesChoice) {
  const ScopedEnvironment gl("WEFT_GL", "");
  EXPECT_EQ(gl_backend_from_environment(render::GlBackend::osmesa), render::GlBackend::osmesa);
  ::unsetenv("WEFT_GL");
  EXPECT_EQ(gl_backend_from_environment(render::GlBackend::egl), render::GlBackend::egl);
}

TEST(GlEnvironment, BadValueIsNamed) {
  const ScopedEnvironment gl("WEFT_GL", "metal");
  render::RenderSettings settings;
  settings.width = settings.height = 8;
  try {
    make_chosen_renderer(settings);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("WEFT_GL"), std::string::npos) << message;
    EXPECT_NE(message.find("'egl'"), std::string::npos) << message;
  }
}

TEST(GlEnvironment, OverridesTheScenesChoice) {
  const ScopedEnvironment gl("WEFT_GL", "egl");
  EXPECT_EQ(gl_backend_from_environment(render::GlBackend::osmesa), render::GlBackend::egl);
  render::RenderSettings settings;
  settings.width = settings.height = 8;
  settings.gl = render::GlBackend::osmesa;
  std::unique_ptr<render::Renderer> renderer;
  try {
    renderer = make_chosen_renderer(settings);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no EGL context: " << e.what();
  }
  EXPECT_NE(renderer->description().find("EGL"), std::string::npos) << renderer->description();
}

}  // namespace
}  // namespace weft::app
