// The turntable's camera path (app/run/orbit_camera.h) and the framing of a mesh file
// (app/cli/turntable_command.h): azimuths 360°·i/N about the vertical through the centre, constant
// distance and elevation, frame 0 = the base camera; the whole mesh inside the field of view.
#include "app/run/orbit_camera.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "app/cli/turntable_command.h"
#include "base/constants.h"

namespace {

using weft::app::orbit_camera;
using weft::app::OrbitSettings;
using weft::render::Camera;
using Eigen::Vector3d;
constexpr double tol = 1e-12;

Camera scene_camera() {
  Camera c;
  c.eye = {0.45, -0.55, 0.55};
  c.target = {0.0, 0.0, 0.2};
  c.fov_y_deg = 35.0;
  return c;
}

double elevation_deg(const Vector3d& offset) {
  return std::atan2(offset.z(), std::hypot(offset.x(), offset.y())) * 180.0 / weft::base::kPi;
}

// Azimuth of the horizontal part of `offset`, degrees in [0, 360).
double azimuth_deg(const Vector3d& offset) {
  const double a = std::atan2(offset.y(), offset.x()) * 180.0 / weft::base::kPi;
  return a < 0.0 ? a + 360.0 : a;
}

double wrapped_difference_deg(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d < 0.0) d += 360.0;
  return d;
}

TEST(OrbitCamera, FrameZeroIsTheBaseCameraWhenItLooksAtTheCentre) {
  const Camera base = scene_camera();
  const Camera c = orbit_camera(base, base.target, 0, 36);
  EXPECT_EQ(c.eye, base.eye);
  EXPECT_EQ(c.target, base.target);
  EXPECT_EQ(c.up, base.up);
  EXPECT_EQ(c.fov_y_deg, base.fov_y_deg);
  EXPECT_EQ(c.near_m, base.near_m);
  EXPECT_EQ(c.far_m, base.far_m);
}

TEST(OrbitCamera, AzimuthsStepBy360OverNAtConstantDistanceAndElevation) {
  const Camera base = scene_camera();
  const Vector3d center(0.01, -0.02, 0.15);  // the cloth's bounding-box centre, off the target
  const Vector3d base_offset = base.eye - base.target;
  for (int n : {1, 4, 7, 12, 36}) {
    for (int i = 0; i < n; ++i) {
      const Camera c = orbit_camera(base, center, i, n);
      const Vector3d offset = c.eye - center;
      EXPECT_EQ(c.target, center);
      EXPECT_NEAR(offset.norm(), base_offset.norm(), tol) << i << "/" << n;
      EXPECT_NEAR(elevation_deg(offset), elevation_deg(base_offset), 1e-9) << i << "/" << n;
      const double turned = wrapped_difference_deg(azimuth_deg(offset), azimuth_deg(base_offset));
      const double expected = 360.0 * i / n;
      EXPECT_NEAR(std::min(std::fabs(turned - expected), 360.0 - std::fabs(turned - expected)),
                  0.0, 1e-9)
          << i << "/" << n;
      // Up turns with the camera: the default z up stays z up.
      EXPECT_NEAR((c.up - Vector3d::UnitZ()).norm(), 0.0, tol);
    }
  }
}

TEST(OrbitCamera, AQuarterTurnIsCounterClockwiseSeenFromAbove) {
  Camera base;
  base.target = Vector3d::Zero();
  base.eye = {2.0, 0.0, 1.0};  // on +x
  const Camera c = orbit_camera(base, Vector3d::Zero(), 1, 4);
  EXPECT_NEAR((c.eye - Vector3d(0.0, 2.0, 1.0)).norm(), 0.0, tol);  // +x → +y
}

TEST(OrbitCamera, ElevationAndDistanceOverrides) {
  const Camera base = scene_camera();
  const Vector3d center(0.0, 0.0, 0.2);
  OrbitSettings settings;
  settings.elevation_deg = 20.0;
  settings.distance_scale = 1.5;
  const double d0 = (base.eye - base.target).norm();
  for (int i = 0; i < 8; ++i) {
    const Vector3d offset = orbit_camera(base, center, i, 8, settings).eye - center;
    EXPECT_NEAR(offset.norm(), 1.5 * d0, tol);
    EXPECT_NEAR(elevation_deg(offset), 20.0, 1e-9);
  }
  // Frame 0 keeps the base camera's azimuth.
  const Vector3d first = orbit_camera(base, center, 0, 8, settings).eye - center;
  EXPECT_NEAR(azimuth_deg(first), azimuth_deg(base.eye - base.target), 1e-9);
}

TEST(OrbitCamera, CameraStraightAboveGetsAnOrbitWhenGivenAnElevation) {
  Camera base;
  base.target = Vector3d::Zero();
  base.eye = {0.0, 0.0, 3.0};
  base.up = Vector3d::UnitY();
  OrbitSettings settings;
  settings.elevation_deg = 45.0;
  const Vector3d offset = orbit_camera(base, Vector3d::Zero(), 0, 4, settings).eye;
  EXPECT_NEAR(offset.norm(), 3.0, tol);
  EXPECT_NEAR(elevation_deg(offset), 45.0, 1e-9);
}

TEST(OrbitCamera, BadArgumentsThrow) {
  const Camera base = scene_camera();
  EXPECT_THROW(orbit_camera(base, base.target, 0, 0), std::invalid_argument);
  EXPECT_THROW(orbit_camera(base, base.target, 4, 4), std::invalid_argument);
  EXPECT_THROW(orbit_camera(base, base.target, -1, 4), std::invalid_argument);
  OrbitSettings steep;
  steep.elevation_deg = 90.0;
  EXPECT_THROW(orbit_camera(base, base.target, 0, 4, steep), std::invalid_argument);
  OrbitSettings zero;
  zero.distance_scale = 0.0;
  EXPECT_THROW(orbit_camera(base, base.target, 0, 4, zero), std::invalid_argument);
  Camera degenerate = base;
  degenerate.eye = degenerate.target;
  EXPECT_THROW(orbit_camera(degenerate, base.target, 0, 4), std::invalid_argument);
}

// Every corner of the box is inside the view frustum of the framing camera, from any azimuth of
// the orbit (the bounding sphere fits the narrower field of view).
TEST(FramingCamera, TheWholeBoxIsInViewAllAroundTheOrbit) {
  const Vector3d lo(-1.0, -0.5, 0.0), hi(1.0, 0.5, 0.3);
  const double fov_y = 40.0, aspect = 4.0 / 3.0;
  const Camera base = weft::app::framing_camera(lo, hi, Vector3d(2.0, -2.5, 0.7), fov_y, aspect);
  EXPECT_NEAR((base.target - 0.5 * (lo + hi)).norm(), 0.0, tol);
  const double tan_y = std::tan(0.5 * fov_y * weft::base::kPi / 180.0), tan_x = aspect * tan_y;
  for (int i = 0; i < 12; ++i) {
    const Camera c = orbit_camera(base, base.target, i, 12);
    const Vector3d forward = (c.target - c.eye).normalized();
    const Vector3d right = forward.cross(c.up).normalized();
    const Vector3d up = right.cross(forward);
    for (int k = 0; k < 8; ++k) {
      const Vector3d corner(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                            k & 4 ? hi.z() : lo.z());
      const Vector3d v = corner - c.eye;
      const double depth = v.dot(forward);
      ASSERT_GT(depth, c.near_m);
      EXPECT_LT(std::fabs(v.dot(right)) / depth, tan_x) << "frame " << i << " corner " << k;
      EXPECT_LT(std::fabs(v.dot(up)) / depth, tan_y) << "frame " << i << " corner " << k;
    }
  }
}

}  // namespace
