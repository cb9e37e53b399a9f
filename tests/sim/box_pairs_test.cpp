// Overlapping box pairs on a grid (sim/collision/box_pairs.h) against testing every pair: boxes
// of mixed sizes, boxes that only touch, points, one box far from the rest, boxes far larger
// than the grid's cells, and boxes that are not finite.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "sim/collision/box_pairs.h"

namespace weft::sim {
namespace {

std::vector<std::array<Index, 2>> every_overlapping_pair(const std::vector<Aabb>& boxes) {
  const auto finite = [](const Aabb& b) { return b.lo.allFinite() && b.hi.allFinite(); };
  std::vector<std::array<Index, 2>> pairs;
  for (std::size_t a = 0; a < boxes.size(); ++a)
    for (std::size_t b = a + 1; b < boxes.size(); ++b)
      if (finite(boxes[a]) && finite(boxes[b]) && boxes_overlap(boxes[a], boxes[b]))
        pairs.push_back({static_cast<Index>(a), static_cast<Index>(b)});
  return pairs;
}

Aabb box_at(const Vec3& lo, const Vec3& size) { return {lo, lo + size}; }

TEST(BoxPairs, FindsExactlyTheOverlappingPairsOfRandomBoxes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> where(0.0, 1.0), size(0.0, 0.12);
  BoxPairs grid;
  std::vector<std::array<Index, 2>> found;
  for (const std::size_t count : {2u, 3u, 50u, 400u, 1500u}) {
    std::vector<Aabb> boxes;
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3 lo(where(rng), where(rng), 0.3 * where(rng));
      boxes.push_back(box_at(lo, Vec3(size(rng), size(rng), size(rng))));
    }
    grid.find(boxes, found);
    EXPECT_EQ(found, every_overlapping_pair(boxes)) << count << " boxes";
  }
}

TEST(BoxPairs, CountsTouchingBoxesPointsAndOutliersAsTestingEveryPairDoes) {
  std::vector<Aabb> boxes;
  // A row of unit boxes each touching the next along x, and points on their shared faces.
  for (int i = 0; i < 10; ++i) boxes.push_back(box_at(Vec3(i, 0, 0), Vec3(1, 1, 1)));
  for (int i = 1; i < 10; ++i) boxes.push_back(box_at(Vec3(i, 0.5, 0.5), Vec3::Zero()));
  boxes.push_back(box_at(Vec3(1e6, 1e6, -1e6), Vec3(1, 1, 1)));      // far from the rest
  boxes.push_back(box_at(Vec3(1e6, 1e6, -1e6), Vec3(0.5, 0.5, 0.5)));  // and its neighbour
  boxes.push_back(box_at(Vec3(-2, -2, -2), Vec3(20, 4, 4)));          // spans every cell
  BoxPairs grid;
  std::vector<std::array<Index, 2>> found;
  grid.find(boxes, found);
  EXPECT_EQ(found, every_overlapping_pair(boxes));
  EXPECT_FALSE(found.empty());
}

// Boxes far larger than the grid's cells (a torn cloth's patches spanning the scene) stay out
// of the grid, which would otherwise hold each of them in every cell: each is tested against
// every box, and a pair of two of them is reported once.
TEST(BoxPairs, BoxesFarLargerThanTheRestArePairedOnceWithEveryBoxTheyOverlap) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> where(0.0, 1.0);
  std::vector<Aabb> boxes;
  for (int i = 0; i < 600; ++i)
    boxes.push_back(box_at(Vec3(where(rng), where(rng), where(rng)), Vec3::Constant(0.02)));
  for (int i = 0; i < 5; ++i)  // overlapping one another and much of the rest
    boxes.insert(boxes.begin() + 100 * i, box_at(Vec3(0.1 * i, 0.0, 0.0), Vec3(0.6, 1.0, 1.0)));
  BoxPairs grid;
  std::vector<std::array<Index, 2>> found;
  grid.find(boxes, found);
  const auto expected = every_overlapping_pair(boxes);
  EXPECT_EQ(found, expected);
  EXPECT_GT(expected.size(), 5u * 200u);
}

TEST(BoxPairs, BoxesThatAreNotFiniteOverlapNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Aabb> boxes{box_at(Vec3(0, 0, 0), Vec3(1, 1, 1)), box_at(Vec3(0.5, 0.5, 0.5), Vec3(1, 1, 1)),
                          Aabb{Vec3(nan, 0, 0), Vec3(1, 1, 1)}, Aabb{Vec3(-inf, -inf, -inf), Vec3(inf, inf, inf)}};
  BoxPairs grid;
  std::vector<std::array<Index, 2>> found;
  grid.find(boxes, found);
  EXPECT_EQ(found, (std::vector<std::array<Index, 2>>{{0, 1}}));
  boxes.resize(1);
  grid.find(boxes, found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace weft::sim
