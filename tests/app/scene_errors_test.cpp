// Bad scene files: each class of mistake gets a message naming the file, the key path and what
// was expected.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

using test::scene_error_of;
using test::scene_error_of_text;

// A valid scene on a 33×33 grid (vertices 0..1088), to be broken one key at a time.
Json valid_scene() {
  return Json::parse(R"({
    "description": "test scene",
    "cloth": {
      "size": ["1 m", "1 m"],
      "resolution": [33, 33],
      "material": {"density": "0.019 gf/cm^2"},
      "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]
    },
    "simulation": {"air_damping": 1},
    "output": {"fps": 24, "frames": 72},
    "render": {"shading": "lit"}
  })");
}

TEST(InputErrors, TheValidSceneIsValid) {
  EXPECT_EQ(scene_error_of(valid_scene()), "no error");
}

TEST(InputErrors, MalformedJsonNamesLineAndColumn) {
  const std::string text = "{\n  \"description\": \"x\",\n  \"cloth\": {\"size\": [1, 1,]}\n}\n";
  const std::string message = scene_error_of_text(text);
  EXPECT_EQ(message.rfind("scene.json:3:27: malformed JSON: ", 0), 0u) << message;
  EXPECT_CONTAINS(message, "unexpected ']'");
  EXPECT_EQ(scene_error_of_text("{\"description\": \"x\"").rfind("scene.json:1:20: malformed JSON:", 0),
            0u);
  EXPECT_EQ(scene_error_of_text("").rfind("scene.json:1:1: malformed JSON:", 0), 0u);
  EXPECT_EQ(scene_error_of_text("[1, 2]"),
            "scene.json: expected a JSON object at the top level, got the array [1,2]");
}

TEST(InputErrors, DuplicateKey) {
  EXPECT_EQ(scene_error_of_text(R"({"description": "x", "output": {"fps": 24, "fps": 30}})"),
            "scene.json: output.fps: duplicate key (each key may appear once in an object)");
}

TEST(InputErrors, UnknownKeyAtTopLevel) {
  Json s = valid_scene();
  s["simulaton"] = Json::object();
  EXPECT_EQ(scene_error_of(s),
            "scene.json: simulaton: unknown key; did you mean 'simulation'? "
            "(known keys here: description, cloth, obstacles, simulation, output, render)");
  s = valid_scene();
  s["comment"] = "hello";
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: comment: unknown key (known keys here:");
}

TEST(InputErrors, UnknownKeyNestedNamesItsPath) {
  Json s = valid_scene();
  s["cloth"]["materal"] = Json::object();
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.materal: unknown key; did you mean 'material'? (known keys here: "
            "mesh, size, resolution, shape, edge, origin, warp_axis, weft_axis, initial_shape, "
            "material, pins)");
  s = valid_scene();
  s["cloth"]["material"]["densty"] = 0.2;
  EXPECT_CONTAINS(scene_error_of(s),
                  "scene.json: cloth.material.densty: unknown key; did you mean 'density'?");
  s = valid_scene();
  s["cloth"]["pins"][1]["cornr"] = "u0v0";
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: cloth.pins[1].cornr: unknown key");
  s = valid_scene();
  s["render"]["camera"] = {{"fov_deg", 30}};
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: render.camera.fov_deg: unknown key");
}

TEST(InputErrors, RequiredKeysMissing) {
  Json s = valid_scene();
  s.erase("description");
  EXPECT_EQ(scene_error_of(s), "scene.json: description: required key is missing (expected a string)");
  s = valid_scene();
  s["clothh"] = s["cloth"];
  s.erase("cloth");
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth: required key is missing (expected an object); is 'clothh' a "
            "misspelling?");
  s = valid_scene();
  s["cloth"].erase("resolution");
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: cloth.resolution: required key is missing");
  s = valid_scene();
  s["description"] = "  ";
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: description: expected a non-empty string");
}

TEST(InputErrors, WrongType) {
  Json s = valid_scene();
  s["cloth"]["resolution"] = "33x33";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.resolution: expected an array of 2 integers in [2, 4096], got the "
            "string '33x33'");
  s = valid_scene();
  s["output"]["fps"] = "24";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: output.fps: expected a number in (0, 1000], got the string '24'");
  s = valid_scene();
  s["description"] = 5;
  EXPECT_EQ(scene_error_of(s), "scene.json: description: expected a string, got 5");
  s = valid_scene();
  s["cloth"]["material"]["shear"] = true;
  EXPECT_CONTAINS(scene_error_of(s),
                  "scene.json: cloth.material.shear: expected a force per length such as N/m or "
                  "gf/cm (a number in SI units or a string with a unit), got true");
  s = valid_scene();
  s["cloth"]["resolution"] = {33, 33.5};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.resolution[1]: expected an integer in [2, 4096], got 33.5");
  s = valid_scene();
  s["cloth"]["size"] = {1, 1, 1};
  EXPECT_CONTAINS(scene_error_of(s),
                  "scene.json: cloth.size: expected an array of 2 values, each a "
                  "length such as m, cm or mm, got the array [1,1,1]");
  s = valid_scene();
  s["render"]["ground"] = "no";
  EXPECT_CONTAINS(scene_error_of(s),
                  "scene.json: render.ground: expected an object, got the string 'no'");
  s = valid_scene();
  s["cloth"]["pins"] = {{"corner", "u0v0"}};
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: cloth.pins: expected an array of objects");
  s = valid_scene();
  s["cloth"]["pins"] = {5};
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: cloth.pins[0]: expected an object, got 5");
}

TEST(InputErrors, WrongDimension) {
  Json s = valid_scene();
  s["cloth"]["material"]["density"] = "0.019 gf/cm";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.material.density: expected an areal density such as kg/m^2, g/m^2 "
            "or gf/cm^2, got '0.019 gf/cm' (that is a force per length)");
  s = valid_scene();
  s["simulation"]["time_step"] = "fast";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: simulation.time_step: expected 'auto', 'adaptive' or a time such as s or ms, "
            "got "
            "'fast' (it does not start with a number)");
}

TEST(InputErrors, OutOfRange) {
  Json s = valid_scene();
  s["cloth"]["resolution"] = {0, 33};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.resolution[0]: expected an integer in [2, 4096], got 0");
  s["cloth"]["resolution"] = {33, 1};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.resolution[1]: expected an integer in [2, 4096], got 1");
  s["cloth"]["resolution"] = {5000, 33};
  EXPECT_CONTAINS(scene_error_of(s), "cloth.resolution[0]: expected an integer in [2, 4096], got 5000");
  s = valid_scene();
  s["cloth"]["material"]["density"] = "-0.019 gf/cm^2";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.material.density: expected an areal density > 0 kg/m^2, got "
            "'-0.019 gf/cm^2' = -0.19 kg/m^2");
  s["cloth"]["material"]["density"] = -1;
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.material.density: expected an areal density > 0 kg/m^2, got -1");
  s = valid_scene();
  s["cloth"]["size"] = {"1 m", "0 mm"};
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: cloth.size[1]: expected a length > 0 m, got '0 mm'");
  s = valid_scene();
  s["output"]["frames"] = 0;
  EXPECT_EQ(scene_error_of(s), "scene.json: output.frames: expected an integer in [1, 100000], got 0");
  s = valid_scene();
  s["output"]["fps"] = 0;
  EXPECT_EQ(scene_error_of(s), "scene.json: output.fps: expected a number in (0, 1000], got 0");
  s = valid_scene();
  s["simulation"]["time_step_safety"] = 1.5;
  EXPECT_CONTAINS(scene_error_of(s), "simulation.time_step_safety: expected a number in (0, 1], got 1.5");
  s = valid_scene();
  s["simulation"]["air_damping"] = "-1 1/s";
  EXPECT_CONTAINS(scene_error_of(s), "simulation.air_damping: expected an inverse time ≥ 0 1/s");
  s = valid_scene();
  s["simulation"]["time_step"] = "-1 ms";
  EXPECT_CONTAINS(scene_error_of(s),
                  "simulation.time_step: expected a time > 0 s, got '-1 ms' = -0.001 s");
  s = valid_scene();
  s["render"]["colors"] = {{"front", {1.2, 0, 0}}};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: render.colors.front[0]: expected a number in [0, 1], got 1.2");
  s = valid_scene();
  s["render"]["msaa"] = 3;
  EXPECT_EQ(scene_error_of(s), "scene.json: render.msaa: expected 1, 2, 4 or 8 samples, got 3");
  s = valid_scene();
  s["render"]["size"] = {8, 480};
  EXPECT_CONTAINS(scene_error_of(s), "render.size[0]: expected an integer in [16, 8192], got 8");
  s = valid_scene();
  s["render"]["camera"] = {{"fov", "180 deg"}};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: render.camera.fov: expected an angle in (0, 180) deg, got '180 deg'");
}

TEST(InputErrors, NonFinite) {
  Json s = valid_scene();
  s["cloth"]["material"]["density"] = "nan";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.material.density: expected an areal density such as kg/m^2, "
            "g/m^2 or gf/cm^2, got 'nan' (not a finite number)");
  s["cloth"]["material"]["density"] = "inf kg/m^2";
  EXPECT_CONTAINS(scene_error_of(s), "cloth.material.density: expected an areal density");
  EXPECT_CONTAINS(scene_error_of(s), "(not a finite number)");
  // 1e999 overflows a double while the JSON is read: the message has the line and column too.
  const std::string text =
      "{\"description\": \"x\",\n \"cloth\": {\"size\": [1, 1], \"resolution\": [3, 3],\n"
      "  \"material\": {\"density\": 1e999}}}";
  EXPECT_EQ(scene_error_of_text(text),
            "scene.json:3:27: cloth.material.density: expected a finite number, got 1e999 (too "
            "large for a double)");
  EXPECT_EQ(scene_error_of_text("{\"simulation\": {\"gravity\": [0, 0, -1e999]}}"),
            "scene.json:1:35: simulation.gravity[2]: expected a finite number, got -1e999 (too "
            "large for a double)");
}

TEST(InputErrors, WrongEnumListsTheChoices) {
  Json s = valid_scene();
  s["render"]["shading"] = "flat";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: render.shading: expected one of 'lit', 'normals', 'strain', got the string 'flat'");
  s = valid_scene();
  s["simulation"]["integrator"] = "rk9";
  EXPECT_EQ(scene_error_of(s),
            "scene.json: simulation.integrator: expected one of 'symplectic_euler', "
            "'implicit_euler', 'explicit_euler', 'rk4', 'velocity_verlet', 'central_difference', "
            "'dynamic_relaxation', got the string 'rk9'");
  s = valid_scene();
  s["simulation"]["model"] = 1;
  EXPECT_EQ(scene_error_of(s), "scene.json: simulation.model: expected one of 'mass_spring', 'baraff_witkin', 'rft3', 'rft6', got 1");
}

TEST(InputErrors, PinsOutsideTheMesh) {
  Json s = valid_scene();
  s["cloth"]["pins"][1] = {{"vertex", 5000}};
  EXPECT_EQ(scene_error_of(s), "scene.json: cloth.pins[1]: vertex 5000 is outside the mesh (0..1088)");
  s["cloth"]["pins"][1] = {{"vertex", -1}};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.pins[1].vertex: expected an integer in [0, 2147483647], got -1");
  s["cloth"]["pins"][1] = {{"grid", {33, 0}}};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.pins[1]: grid vertex [33, 0] is outside the mesh ([0..32, 0..32])");
  s["cloth"]["pins"][0] = {{"corner", "u0v2"}};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.pins[0]: unknown corner 'u0v2' (choices: u0v0, u1v0, u0v1, u1v1)");
  s = valid_scene();
  s["cloth"]["pins"].push_back({{"region", {{"u", {0.51, 0.52}}, {"v", {0.51, 0.52}}}}});
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: cloth.pins[2]: region u [0.51");
  EXPECT_CONTAINS(scene_error_of(s), "contains no vertex");
  s["cloth"]["pins"][2] = {{"region", {{"u", {0.6, 0.4}}, {"v", {0, 1}}}}};
  EXPECT_CONTAINS(scene_error_of(s),
                  "scene.json: cloth.pins[2].region.u: expected [min, max] with min ≤ max");
  s["cloth"]["pins"][2] = {{"region", {{"u", {0, 1.5}}, {"v", {0, 1}}}}};
  EXPECT_CONTAINS(scene_error_of(s), "cloth.pins[2].region.u[1]: expected a number in [0, 1], got 1.5");
  s["cloth"]["pins"][2] = {{"corner", "u0v0"}, {"vertex", 3}};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.pins[2]: expected exactly one of 'corner', 'vertex', 'grid', "
            "'region', 'box', 'color', got both 'corner' and 'vertex'");
  s["cloth"]["pins"][2] = Json::object();
  EXPECT_CONTAINS(scene_error_of(s),
                  "cloth.pins[2]: expected exactly one of 'corner', 'vertex', "
                  "'grid', 'region', 'box', 'color', got none of them");
}

TEST(InputErrors, Geometry) {
  Json s = valid_scene();
  s["cloth"]["warp_axis"] = {1, 1, 0};
  EXPECT_EQ(
      scene_error_of(s),
      "scene.json: cloth.warp_axis: expected a unit vector, got [1, 1, 0] (length 1.41421356)");
  s = valid_scene();
  s["cloth"]["weft_axis"] = {0.6, 0.8, 0};
  EXPECT_EQ(scene_error_of(s),
            "scene.json: cloth.weft_axis: expected a unit vector orthogonal to warp_axis, got one "
            "at 53.1301 deg to it");
  s = valid_scene();
  s["render"]["camera"] = {{"eye", {0, 0, 5}}, {"target", {0, 0, 0}}};
  EXPECT_CONTAINS(scene_error_of(s),
                  "scene.json: render.camera.up: expected a direction that is not "
                  "zero and not parallel to target - eye");
  s = valid_scene();
  s["render"]["light"] = {{"direction", {0, 0, 0}}};
  EXPECT_CONTAINS(scene_error_of(s), "scene.json: render.light.direction: expected a non-zero vector");
}

TEST(InputErrors, MissingOrUnreadableFile) {
  try {
    load_scene("/nonexistent/weft/missing.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(
        e.what(),
        "/nonexistent/weft/missing.json: cannot read scene file (No such file or directory)");
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  try {
    load_scene(dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.string() + ": cannot read scene file (Is a directory)");
  }
}

TEST(InputErrors, ErrorsFromAFileNameItsPath) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "weft_scene_errors_bad.json";
  Json s = valid_scene();
  s["output"]["frames"] = -3;
  std::ofstream(path) << s.dump(2);
  try {
    load_scene(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path.string() + ": output.frames: expected an integer in [1, 100000], got -3");
  }
  std::filesystem::remove(path);
}

TEST(InputErrors, RendererAndRayTraceSettings) {
  Json s = valid_scene();
  s["render"]["renderer"] = "pathtracer";
  EXPECT_CONTAINS(scene_error_of(s), "render.renderer: expected one of 'raster', 'raytrace'");
  s = valid_scene();
  s["render"]["raytrace"] = {{"samples", 0}};
  EXPECT_CONTAINS(scene_error_of(s), "render.raytrace.samples: expected an integer in [1, 65536], got 0");
  s = valid_scene();
  s["render"]["raytrace"] = {{"spp", 4}};
  EXPECT_CONTAINS(scene_error_of(s), "render.raytrace.spp: unknown key");
  s = valid_scene();
  s["render"]["raytrace"] = {{"sun_radius", "50 deg"}};
  EXPECT_CONTAINS(scene_error_of(s), "render.raytrace.sun_radius: expected an angle in [0, 45] deg");

  s = valid_scene();
  s["render"]["raytrace"] = {{"sheen", 0.2}};
  EXPECT_CONTAINS(scene_error_of(s), "render.raytrace.sheen: expected it in \"render\": render.sheen");
  s = valid_scene();
  s["render"]["sheen_roughness"] = 0;
  EXPECT_CONTAINS(scene_error_of(s), "render.sheen_roughness");

  s = valid_scene();
  s["render"]["renderer"] = "raytrace";
  s["render"]["raytrace"] = {{"samples", 4}, {"bounces", 2}, {"ao_distance", "20 cm"},
                             {"sun_radius", "1 deg"}};
  s["render"]["sheen"] = 0;
  const Scene scene = parse_scene(s.dump(), "scene.json");
  EXPECT_EQ(scene.render.renderer, render::RendererKind::raytrace);
  EXPECT_EQ(scene.render.raytrace.samples_per_pixel, 4);
  EXPECT_EQ(scene.render.raytrace.bounces, 2);
  EXPECT_DOUBLE_EQ(scene.render.raytrace.ao_distance_m, 0.2);
  EXPECT_DOUBLE_EQ(scene.render.raytrace.sun_angular_radius_deg, 1.0);
  EXPECT_EQ(scene.render.cloth_surface.sheen, 0.0);
}

}  // namespace
}  // namespace weft::app
