// The time left of a run (app/run/run_eta.h): simulated and drawn frames keep their own costs,
// so a run that draws a few of its frames is not told that every frame costs a drawn one, and a
// frame being drawn predicts itself from its share done.

#include <gtest/gtest.h>

#include "app/run/run_eta.h"

namespace weft::app {
namespace {

TEST(RunEta, DrawnAndSimulatedFramesKeepTheirOwnCosts) {
  // The run: 96 frames simulated at ~0.2 s each, 4 drawn at ~23 s (the first is one of
  // them). After frame 1, Progress's elapsed × left / done said 95 × 23.2 s = 37 min.
  RunEta eta;
  eta.add_simulated(0.2);
  eta.add_drawn(23.0);
  EXPECT_NEAR(eta.seconds_left(95, 3), 95 * 0.2 + 3 * 23.0, 1e-9);  // 88 s
  // More frames: the means move with them.
  eta.add_simulated(0.4);
  eta.add_drawn(25.0);
  EXPECT_NEAR(eta.seconds_left(10, 1), 10 * 0.3 + 24.0, 1e-9);
  EXPECT_NEAR(eta.seconds_left(0, 0), 0.0, 1e-12);
}

TEST(RunEta, AFrameBeingDrawnPredictsItselfFromItsShareDone) {
  RunEta eta;
  eta.add_simulated(0.5);
  // The first frame drawn, a quarter done after 5 s: 15 s more, and 20 s for each frame after.
  EXPECT_NEAR(eta.seconds_left(9, 2, 0.25, 5.0), 9 * 0.5 + 15.0 + 2 * 20.0, 1e-9);
  // Nothing known of drawing, nothing being drawn, frames to draw: not known yet.
  EXPECT_LT(eta.seconds_left(9, 2), 0.0);
  // Nothing simulated yet, frames to simulate: not known either.
  EXPECT_LT(RunEta().seconds_left(3, 0), 0.0);
  // Frames drawn before: under a tenth done, their mean predicts the current one's rest.
  eta.add_drawn(30.0);
  EXPECT_NEAR(eta.seconds_left(0, 0, 0.05, 1.0), 29.0, 1e-9);
  EXPECT_NEAR(eta.seconds_left(0, 0, 0.5, 20.0), 20.0, 1e-9);  // then its own rate: 40 s in all
}

}  // namespace
}  // namespace weft::app
