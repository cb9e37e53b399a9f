// Moving pins in scene files: "cloth.pins[k].path" keyframes land in Scene::pin_paths, one per
// pin, and every mistake names its key path.
#include <gtest/gtest.h>

#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

using test::scene_error_of;

Json scene_with_pins(const Json& pins) {
  Json j = Json::parse(R"({
    "description": "moving pins",
    "cloth": {"size": ["40 cm", "40 cm"], "resolution": [9, 9]}
  })");
  j["cloth"]["pins"] = pins;
  return j;
}

TEST(PinPathScene, KeyframesLandInThePinsPath) {
  const Json pins = Json::parse(R"([
    {"corner": "u0v1"},
    {"corner": "u1v1", "path": [{"time": "0 s", "offset": [0, 0, 0]},
                                {"time": "500 ms", "offset": ["-20 cm", "0 m", "10 cm"]}]}
  ])");
  const Scene scene = parse_scene(scene_with_pins(pins).dump(2), "scene.json");
  ASSERT_EQ(scene.pin_paths.size(), 2u);
  EXPECT_FALSE(scene.pin_paths[0].moves());
  ASSERT_TRUE(scene.pin_paths[1].moves());
  ASSERT_EQ(scene.pin_paths[1].keyframes().size(), 2u);
  EXPECT_DOUBLE_EQ(scene.pin_paths[1].keyframes()[1].time_s, 0.5);
  EXPECT_TRUE(scene.pin_paths[1].offset_at(0.25).isApprox(sim::Vec3(-0.1, 0.0, 0.05)));
}

TEST(PinPathScene, MistakesNameTheKeyframe) {
  Json pins = Json::parse(R"([{"corner": "u0v1", "path": []}])");
  EXPECT_EQ(scene_error_of(scene_with_pins(pins)),
            "scene.json: cloth.pins[0].path: expected at least one keyframe, got an empty list");
  pins = Json::parse(R"([{"corner": "u0v1", "path": [{"time": "1 s", "offset": [0, 0, 0]},
                                                      {"time": "1 s", "offset": [0, 0, 1]}]}])");
  EXPECT_EQ(scene_error_of(scene_with_pins(pins)),
            "scene.json: cloth.pins[0].path: keyframe 1: time 1 s is not after keyframe 0's 1 s");
  pins = Json::parse(R"([{"corner": "u0v1", "path": [{"time": "1 s"}]}])");
  EXPECT_NE(scene_error_of(scene_with_pins(pins)).find("cloth.pins[0].path[0].offset"), std::string::npos)
      << scene_error_of(scene_with_pins(pins));
  pins = Json::parse(R"([{"corner": "u0v1", "path": [{"time": "1 kg", "offset": [0, 0, 0]}]}])");
  EXPECT_NE(scene_error_of(scene_with_pins(pins)).find("cloth.pins[0].path[0].time"), std::string::npos)
      << scene_error_of(scene_with_pins(pins));
  pins = Json::parse(R"([{"corner": "u0v1", "path": [{"time": "1 s", "offset": [0, 0, 0], "speed": 2}]}])");
  EXPECT_NE(scene_error_of(scene_with_pins(pins)).find("cloth.pins[0].path[0].speed"), std::string::npos)
      << scene_error_of(scene_with_pins(pins));
}

}  // namespace
}  // namespace weft::app
