// The Cusick drape test (assets/scenes/cusick_drape_round.json: a Ø30 cm specimen on a Ø18 cm
// support), measured as `weft measure` does: the drape coefficient of the wool preset lies in
// the 0.3–0.9 range the issue asks of it, and grows with bending rigidity — a stiffer fabric
// stands out further. Three fabrics that differ only in bending (the wool's B/4, B, 4B), so
// that nothing but bending changes. Coarser than the scene file (41 × 41: 20 rings, 2 s) to
// keep the three runs within seconds; the full scene (40 rings, 3 s) gives DC 0.458 with 8
// folds (gallery/). On 15 rings (31 × 31) the soft wool's ten folds are too coarse to tell it
// from the wool (DC 0.522 against 0.487 at 2 s; 0.376 against 0.507 on 20 rings).

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>

#include "app/run/measure.h"
#include "app/scene/scene.h"
#include "coarse_scene.h"
#include "sim/material/material_presets.h"

namespace weft::app {
namespace {

// The scene's DC at 2 s on n × n (⌊n/2⌋ rings).
double cusick_drape_coefficient(double bending_scale, sim::Index n,
                                const std::string& preset = "wool_kang_yu",
                                std::optional<sim::ClothModel> model = std::nullopt) {
  Scene scene = test::coarse_scene("cusick_drape_round.json", n);
  scene.frames = 48;  // 2 s
  scene.material = sim::material_preset(preset).material;
  if (model) scene.sim.model = *model;
  scene.material.bend_warp_Nm *= bending_scale;
  scene.material.bend_weft_Nm *= bending_scale;
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  const SceneMeasurement m = measure_scene(scene, *simulator, true);
  EXPECT_TRUE(m.final_drape);
  return m.final_drape ? m.final_drape->drape_coefficient : -1.0;
}

TEST(Cusick, WoolDrapeCoefficientIsInRangeAndGrowsWithBendingRigidity) {
  const double soft = cusick_drape_coefficient(0.25, 41);
  const double wool = cusick_drape_coefficient(1.0, 41);
  const double stiff = cusick_drape_coefficient(4.0, 41);
  std::printf("Cusick DC (41 x 41, 2 s): B/4 %.3f, wool B %.3f, 4B %.3f\n", soft, wool, stiff);
  EXPECT_GE(wool, 0.3);
  EXPECT_LE(wool, 0.9);
  EXPECT_LT(soft, wool);
  EXPECT_LT(wool, stiff);
}

// The presets in the Cusick test. None of their sources publishes a drape coefficient
// (sim/material/material_presets.cpp), so this cannot hold the simulation against published DCs; it holds
// it to the finding that DC rises with the cantilever bending length (Cusick, G. E. (1965), "The
// dependence of fabric drape on bending and shear stiffness", J. Textile Inst. 56)
// c = (B/w)^(1/3), on the library's extremes (Wang et al. 2011): the t-shirt interlock, the
// softest (c = 1.25 / 1.47 cm), drapes lower than the polycotton pants fabric, the stiffest
// (2.44 / 2.44 cm). Both on the Baraff–Witkin model: the mass-spring one cannot hold the
// interlock's shear rigidity, which exceeds its warp tensile rigidity (docs/scene.md).
TEST(Cusick, PresetDrapeCoefficientsOrderAsTheirBendingLengths) {
  const auto bw = sim::ClothModel::baraff_witkin;
  const double soft = cusick_drape_coefficient(1.0, 31, "wang2011_gray_interlock", bw);
  const double stiff = cusick_drape_coefficient(1.0, 31, "wang2011_royal_target", bw);
  std::printf("Cusick DC (31 x 31, 2 s, baraff_witkin): wang2011_gray_interlock %.3f, "
              "wang2011_royal_target %.3f\n", soft, stiff);
  EXPECT_LT(soft + 0.1, stiff);
}

}  // namespace
}  // namespace weft::app
