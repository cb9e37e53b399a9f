#pragma once
// Shared by the scene-file tests: parse a JSON scene as "scene.json", or get its error.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/io/mesh_file.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene.h"

#define EXPECT_CONTAINS(message, part) \
  EXPECT_NE((message).find(part), std::string::npos) << "message: " << (message)

namespace weft::app::test {

inline constexpr double gram_force = 9.80665e-3;  // N: one gram under standard gravity

// Relative comparison at 1e-12.
inline void expect_close(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-12 * std::fabs(expected)) << "actual " << actual;
}

// The message load_triangle_mesh throws for `path`, or "no error".
inline std::string mesh_load_error(const std::filesystem::path& path) {
  try {
    load_triangle_mesh(path);
  } catch (const MeshFileError& e) {
    return e.what();
  }
  return "no error";
}

inline Scene parse_json_scene(const Json& scene) {
  return parse_scene(scene.dump(2), "scene.json");
}

// The InputError message of the text read as `source` (its relative paths resolve from there),
// or "no error".
inline std::string scene_error_of_text(const std::string& text,
                                       const std::string& source = "scene.json") {
  try {
    parse_scene(text, source);
  } catch (const InputError& e) {
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

// A size_u × size_v rectangle of nu × nv vertices at height z: vertex (i, j) at (i·du, j·dv, z)
// with texture coordinates (i·du, j·dv) (metres); quads, or each quad cut into two triangles
// along the other diagonal from the grid's (so no grid is found in it). The faces are listed
// last row first, so the file's order is not the grid's.
inline std::string rectangle_obj(int nu, int nv, double size_u, double size_v, double z, bool triangles) {
  std::string s;
  char line[160];
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = i * (size_u / (nu - 1)), v = j * (size_v / (nv - 1));
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\nvt %.17g %.17g\n", u, v, z, u, v);
      s += line;
    }
  const auto id = [&](int i, int j) { return std::to_string(j * nu + i + 1); };
  const auto corner = [&](int i, int j) { return " " + id(i, j) + "/" + id(i, j); };
  for (int j = nv - 2; j >= 0; --j)
    for (int i = 0; i + 1 < nu; ++i) {
      if (triangles) {
        s += "f" + corner(i, j) + corner(i + 1, j) + corner(i, j + 1) + "\n";
        s += "f" + corner(i + 1, j) + corner(i + 1, j + 1) + corner(i, j + 1) + "\n";
      } else {
        s += "f" + corner(i, j) + corner(i + 1, j) + corner(i + 1, j + 1) + corner(i, j + 1) + "\n";
      }
    }
  return s;
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
