// Moving pins' paths (sim::PinPath): piecewise-linear keyframes, validated.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "sim/pin_motion.h"

namespace weft::sim {
namespace {

TEST(PinPath, InterpolatesLinearlyAndHoldsBeyondTheEnds) {
  const PinPath path({{0.5, Vec3(0, 0, 0)}, {1.5, Vec3(0.2, 0, 0.1)}, {2.5, Vec3(0.2, 0, -0.1)}});
  EXPECT_TRUE(path.moves());
  EXPECT_TRUE(path.offset_at(0.0).isZero());                        // before the first
  EXPECT_TRUE(path.offset_at(1.0).isApprox(Vec3(0.1, 0, 0.05)));    // halfway, first segment
  EXPECT_TRUE(path.offset_at(1.5).isApprox(Vec3(0.2, 0, 0.1)));     // on a keyframe
  EXPECT_TRUE(path.offset_at(2.25).isApprox(Vec3(0.2, 0, -0.05)));  // 3/4 of the second
  EXPECT_TRUE(path.offset_at(9.0).isApprox(Vec3(0.2, 0, -0.1)));    // after the last
  EXPECT_FALSE(PinPath().moves());
  EXPECT_TRUE(PinPath().offset_at(1.0).isZero());
}

TEST(PinPath, RejectsUnorderedOrNonFiniteKeyframes) {
  const auto message = [](std::vector<PinKeyframe> frames) {
    try {
      PinPath path(std::move(frames));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({{0.0, Vec3::Zero()}, {0.0, Vec3::Ones()}}),
            "keyframe 1: time 0 s is not after keyframe 0's 0 s");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message({{nan, Vec3::Zero()}}), "keyframe 0: time nan s is not finite");
  EXPECT_EQ(message({{0.0, Vec3(0, nan, 0)}}), "keyframe 0: offset is not finite");
}

}  // namespace
}  // namespace weft::sim
