#include "sim/pins.h"

#include <gtest/gtest.h>

namespace weft::sim {
namespace {

ClothMesh grid_5x4() {
  GridSpec spec;
  spec.nu = 5;
  spec.nv = 4;
  return make_grid(spec);
}

std::string error_of(const std::vector<PinSpec>& pins) {
  try {
    resolve_pins(pins, grid_5x4());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(Pins, CornersByName) {
  const ClothMesh mesh = grid_5x4();
  EXPECT_EQ(resolve_pins({PinCorner{"u0v0"}}, mesh), std::vector<Index>{0});
  EXPECT_EQ(resolve_pins({PinCorner{"u1v0"}}, mesh), std::vector<Index>{4});
  EXPECT_EQ(resolve_pins({PinCorner{"u0v1"}}, mesh), std::vector<Index>{15});
  EXPECT_EQ(resolve_pins({PinCorner{"u1v1"}}, mesh), std::vector<Index>{19});
}

TEST(Pins, RegionIncludesGridLinesOnItsBoundsAndDuplicatesMerge) {
  const ClothMesh mesh = grid_5x4();
  const auto top_row = resolve_pins({PinRegion{0, 1, 1, 1}}, mesh);
  EXPECT_EQ(top_row, (std::vector<Index>{15, 16, 17, 18, 19}));
  const auto merged = resolve_pins({PinRegion{0, 1, 1, 1}, PinCorner{"u1v1"}, PinVertex{15}}, mesh);
  EXPECT_EQ(merged, top_row);
  EXPECT_EQ(resolve_pins({PinGrid{2, 1}}, mesh), std::vector<Index>{7});
}

TEST(Pins, OutsideTheMeshIsAnErrorNamingThePin) {
  EXPECT_EQ(error_of({PinCorner{"u0v0"}, PinVertex{20}}), "pin 1: vertex 20 is outside the mesh (0..19)");
  EXPECT_EQ(error_of({PinGrid{5, 0}}), "pin 0: grid vertex [5, 0] is outside the mesh ([0..4, 0..3])");
  EXPECT_EQ(error_of({PinCorner{"top"}}), "pin 0: unknown corner 'top' (choices: u0v0, u1v0, u0v1, u1v1)");
  EXPECT_NE(error_of({PinRegion{0.3, 0.4, 0.5, 0.6}}).find("contains no vertex"), std::string::npos);
  EXPECT_NE(error_of({PinRegion{0.6, 0.4, 0, 1}}).find("ordered"), std::string::npos);
}

}  // namespace
}  // namespace weft::sim
