// "simulation.aerodynamics" in scene files: the keys land in sim::AeroSettings, absence means
// no aerodynamic term, and mistakes name their key path.

#include <gtest/gtest.h>

#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "sim/simulator.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json aero_scene() {
  return Json::parse(R"({
    "description": "test scene with wind",
    "cloth": {"size": ["40 cm", "40 cm"], "resolution": [5, 5]},
    "simulation": {"aerodynamics": {
      "drag_coefficient": 0.9, "air_density": 1.1,
      "wind": {"velocity": ["3 m/s", 0, "-50 cm/s"],
               "gust": {"amplitude": 0.25, "period": "2 s", "wavelength": "5 m"}}}}
  })");
}

TEST(AeroScene, EveryKeyLands) {
  const sim::AeroSettings a = test::parse_json_scene(aero_scene()).sim.aero;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(a.drag_coefficient, 0.9);
  EXPECT_EQ(a.air_density_kg_m3, 1.1);
  EXPECT_EQ(a.wind.velocity_m_s, sim::Vec3(3, 0, -0.5));
  EXPECT_EQ(a.wind.gust.amplitude, 0.25);
  EXPECT_EQ(a.wind.gust.period_s, 2.0);
  EXPECT_EQ(a.wind.gust.wavelength_m, 5.0);
}

TEST(AeroScene, AbsentMeansOffAnEmptyObjectMeansStillAir) {
  Json j = aero_scene();
  j["simulation"].erase("aerodynamics");
  EXPECT_FALSE(test::parse_json_scene(j).sim.aero.enabled);
  j["simulation"]["aerodynamics"] = Json::object();
  const sim::AeroSettings a = test::parse_json_scene(j).sim.aero;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(a.wind.velocity_m_s, sim::Vec3::Zero());
  EXPECT_EQ(a.drag_coefficient, sim::AeroSettings{}.drag_coefficient);
}

TEST(AeroScene, MistakesNameTheirKey) {
  Json j = aero_scene();
  j["simulation"]["aerodynamics"]["wind"].erase("velocity");
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: simulation.aerodynamics.wind.velocity:");
  j = aero_scene();
  j["simulation"]["aerodynamics"]["wind"]["gust"].erase("period");
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: simulation.aerodynamics.wind.gust.period:");
  j = aero_scene();
  j["simulation"]["aerodynamics"]["drag_coefficient"] = -1;
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: simulation.aerodynamics.drag_coefficient:");
  j = aero_scene();
  j["simulation"]["aerodynamics"]["wind_speed"] = 3;
  EXPECT_CONTAINS(test::scene_error_of(j),
                  "scene.json: simulation.aerodynamics.wind_speed: unknown key");
}

// The simulator builds the drag term only when asked, and --explain says so with its figures.
TEST(AeroScene, ExplainListsTheDragAndWind) {
  const auto forces_line = [](const Json& j) {
    const std::unique_ptr<sim::Simulator> simulator = make_simulator(test::parse_json_scene(j));
    for (const std::string& line : simulator->explain())
      if (line.rfind("forces", 0) == 0) return line;
    return std::string("no forces line");
  };
  const std::string on = forces_line(aero_scene());
  EXPECT_CONTAINS(
      on, "air drag on 16 quads (C_d 0.9, 1.1 kg/m³, wind 3.04138 m/s gusting ±25 % every 2 s)");
  Json j = aero_scene();
  j["simulation"].erase("aerodynamics");
  EXPECT_EQ(forces_line(j).find("air drag"), std::string::npos);
}

}  // namespace
}  // namespace weft::app
