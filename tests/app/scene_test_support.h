#pragma once
// Shared by the scene-file tests: parse a JSON scene as "scene.json", or get its error.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "app/json_reader.h"
#include "app/scene.h"

#define EXPECT_CONTAINS(message, part) \
  EXPECT_NE((message).find(part), std::string::npos) << "message: " << (message)

namespace weft::app::test {

inline constexpr double gram_force = 9.80665e-3;  // N: one gram under standard gravity

// Relative comparison at 1e-12.
inline void expect_close(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-12 * std::fabs(expected)) << "actual " << actual;
}

inline Scene parse_json_scene(const Json& scene) {
  return parse_scene(scene.dump(2), "scene.json");
}

// The SceneError message of the text read as `source` (its relative paths resolve from there),
// or "no error".
inline std::string scene_error_of_text(const std::string& text,
                                       const std::string& source = "scene.json") {
  try {
    parse_scene(text, source);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

inline std::string scene_error_of(const Json& scene) {
  return scene_error_of_text(scene.dump(2));
}

// The same for a scene read as the file `source` (one line of JSON).
inline std::string scene_error_of(const Json& scene, const std::filesystem::path& source) {
  return scene_error_of_text(scene.dump(), source.string());
}


// A small test scene (a 1 m sheet, 9 × 9 vertices, 2 frames) with `render` as its render block.
inline Json scene_with_render(const Json& render) {
  Json s = Json::parse(R"({
    "description": "test scene",
    "cloth": {"size": ["1 m", "1 m"], "resolution": [9, 9],
              "material": {"density": "0.019 gf/cm^2"}},
    "output": {"fps": 24, "frames": 2}
  })");
  s["render"] = render;
  return s;
}

}  // namespace weft::app::test
