// "cloth.material.bending_law" and "cloth.material.stretch_law" in scene files
// (sim/material/bending_law.h, stretch_law.h): one law for both directions or one per
// direction, the rigidity it sets, the "_curves" presets' laws, and the errors naming the key or
// the table point; "simulation.static"; and --set KEY=null, which removes a key (a law beside
// bend_warp).
#include <gtest/gtest.h>

#include <string>

#include "app/scene/scene.h"
#include "app/scene/scene_patch.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json strip_scene() {
  return Json::parse(R"({
    "description": "a strip bending by a law",
    "cloth": {"size": ["10 cm", "2 cm"], "resolution": [11, 3],
              "material": {"bending_law": {"form": "frictional", "B": "0.007 N*m", "M0": "0.25 N",
                                           "kappa0": "0.5 1/m"}}},
    "simulation": {"static": {"seed": 7, "tolerance": 1e-8}}
  })");
}

TEST(BendingLawScene, OneLawSetsBothDirectionsAndTheirInitialRigidity) {
  const Scene s = test::parse_json_scene(strip_scene());
  ASSERT_TRUE(s.material.bend_law_warp && s.material.bend_law_weft);
  EXPECT_EQ(s.material.bend_law_warp->form(), sim::BendingLaw::Form::frictional);
  EXPECT_DOUBLE_EQ(s.material.bend_warp_Nm, 0.007 + 0.25 / 0.5);
  EXPECT_DOUBLE_EQ(s.material.bend_weft_Nm, 0.007 + 0.25 / 0.5);
  EXPECT_EQ(s.sim.statics.seed, 7u);
  EXPECT_DOUBLE_EQ(s.sim.statics.tolerance, 1e-8);
}

TEST(BendingLawScene, PerDirectionTableKeepsTheOtherDirectionLinear) {
  Json j = strip_scene();
  j["cloth"]["material"]["bending_law"] =
      Json::parse(R"({"weft": {"form": "table", "curvature": ["1 1/m", "4 1/m"], "moment": ["0.5 N", "0.8 N"]}})");
  const Scene s = test::parse_json_scene(j);
  EXPECT_FALSE(s.material.bend_law_warp);
  ASSERT_TRUE(s.material.bend_law_weft);
  EXPECT_DOUBLE_EQ(s.material.bend_weft_Nm, 0.5);
  EXPECT_DOUBLE_EQ(s.material.bend_law_weft->moment(4.0), 0.8);
}

TEST(BendingLawScene, ErrorsNameTheKeyOrThePoint) {
  Json j = strip_scene();
  j["cloth"]["material"]["bend_warp"] = "0.05 N*m";
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.bend_warp: the bending law sets this "
                                           "direction's bending rigidity");
  j = strip_scene();
  j["cloth"]["material"]["bending_law"] =
      Json::parse(R"({"form": "table", "curvature": ["1 1/m", "2 1/m"], "moment": ["0.5 N", "0.4 N"]})");
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.bending_law.moment: bending law: table point 2");
  j = strip_scene();
  j["cloth"]["material"]["bending_law"]["form"] = "quartic";
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.bending_law.form");
  j = strip_scene();
  j["simulation"]["model"] = "baraff_witkin";  // refused when the model is built
  try {
    make_simulator(test::parse_json_scene(j));
    ADD_FAILURE() << "a law on baraff_witkin was accepted";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(std::string(e.what()), "a nonlinear bending law needs cloth.model mass_spring");
  }
  j = strip_scene();
  j["simulation"]["static"]["imperfection"] = -1;
  EXPECT_CONTAINS(test::scene_error_of(j), "simulation.static.imperfection");
}

TEST(BendingLawScene, SettingNullRemovesTheKey) {
  Json j = strip_scene();
  j["cloth"]["material"].erase("bending_law");
  j["cloth"]["material"]["bend_warp"] = "0.05 N*m";
  const Scene base = test::parse_json_scene(j);
  const Scene patched = patched_scene(
      base, {{"cloth.material.bend_warp", "null"},
             {"cloth.material.bending_law", R"({"form": "linear", "B": "0.02 N*m"})"}});
  EXPECT_DOUBLE_EQ(patched.material.bend_warp_Nm, 0.02);
  EXPECT_THROW(patched_scene(base, {{"cloth.material.bending_law",
                                     R"({"form": "linear", "B": "0.02 N*m"})"}}),
               InputError);  // bend_warp kept beside the law
}

TEST(StretchLawScene, PerDirectionTableSetsItsInitialStiffness) {
  Json j = strip_scene();
  j["cloth"]["material"]["stretch_law"] =
      Json::parse(R"({"weft": {"form": "table", "strain": [0.01, 0.05], "tension": ["5 N/m", "0.4 N/cm"]}})");
  const Scene s = test::parse_json_scene(j);
  EXPECT_FALSE(s.material.stretch_law_warp);
  ASSERT_TRUE(s.material.stretch_law_weft);
  EXPECT_DOUBLE_EQ(s.material.stretch_weft_N_m, 500.0);  // the first segment's mean slope
  EXPECT_DOUBLE_EQ(s.material.stretch_law_weft->tension(0.05), 40.0);
  j["cloth"]["material"]["stretch_law"] = Json::parse(R"({"form": "linear", "Y": "300 N/m"})");
  const Scene both = test::parse_json_scene(j);
  EXPECT_DOUBLE_EQ(both.material.stretch_warp_N_m, 300.0);
  EXPECT_DOUBLE_EQ(both.material.stretch_weft_N_m, 300.0);
  EXPECT_NO_THROW(make_simulator(both));
}

TEST(StretchLawScene, ErrorsNameTheKeyOrThePoint) {
  Json j = strip_scene();
  j["cloth"]["material"]["stretch_law"] =
      Json::parse(R"({"form": "table", "strain": [0.01, 0.02], "tension": ["5 N/m", "4 N/m"]})");
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.stretch_law.tension: stretch law: table point 2");
  j["cloth"]["material"]["stretch_law"] =
      Json::parse(R"({"form": "table", "strain": [0.01, 0.02], "tension": ["5 N/m"]})");
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.stretch_law.tension");
  j["cloth"]["material"]["stretch_law"] = Json::parse(R"({"form": "linear", "Y": "300 N/m"})");
  j["cloth"]["material"]["stretch_warp"] = "500 N/m";
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.stretch_warp: the stretch law sets this "
                                           "direction's stretch rigidity");
  j = strip_scene();
  j["cloth"]["material"]["stretch_law"] = Json::parse(R"({"form": "linear", "Y": "300 N/m"})");
  j["simulation"]["model"] = "baraff_witkin";
  j["cloth"]["material"].erase("bending_law");
  try {
    make_simulator(test::parse_json_scene(j));
    ADD_FAILURE() << "a stretch law on baraff_witkin was accepted";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(std::string(e.what()), "a nonlinear stretch law needs cloth.model mass_spring");
  }
}

TEST(MaterialLawScene, CurvesPresetCarriesItsLawsAndRefusesARigidityBesideThem) {
  Json j = strip_scene();
  j["cloth"]["material"] = Json::parse(R"({"preset": "wang2011_11oz_black_denim_curves"})");
  const Scene s = test::parse_json_scene(j);
  ASSERT_TRUE(s.material.stretch_law_warp && s.material.stretch_law_weft);
  ASSERT_TRUE(s.material.bend_law_warp && s.material.bend_law_weft);
  EXPECT_NO_THROW(make_simulator(s));
  j["cloth"]["material"]["stretch_weft"] = "2000 N/m";
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.material.stretch_weft: the preset's measured "
                                           "stretch law sets this direction's stretch rigidity");
  j["cloth"]["material"].erase("stretch_weft");
  j["cloth"]["material"]["bend_warp"] = "2e-5 N*m";
  EXPECT_CONTAINS(test::scene_error_of(j), "choose the preset without \"_curves\"");
  // A law given in the scene replaces the preset's.
  j["cloth"]["material"].erase("bend_warp");
  j["cloth"]["material"]["bending_law"] = Json::parse(R"({"warp": {"form": "linear", "B": "2e-5 N*m"}})");
  EXPECT_DOUBLE_EQ(test::parse_json_scene(j).material.bend_warp_Nm, 2e-5);
}

}  // namespace
}  // namespace weft::app
