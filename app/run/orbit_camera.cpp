// The turntable's camera path (see orbit_camera.h).

#include "app/run/orbit_camera.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace weft::app {
namespace {

}  // namespace

double orbit_azimuth_deg(int i, int n) { return 360.0 * i / n; }

render::Camera orbit_camera(const render::Camera& base, const Eigen::Vector3d& center_m, int i,
                            int n, const OrbitSettings& settings) {
  if (n < 1 || i < 0 || i >= n)
    throw std::invalid_argument("orbit_camera: frame " + std::to_string(i) + " of " +
                                std::to_string(n) + ": expected n >= 1 and 0 <= i < n");
  if (!(settings.distance_scale > 0.0) || !std::isfinite(settings.distance_scale))
    throw std::invalid_argument("orbit_camera: distance scale must be finite and > 0");
  if (settings.elevation_deg &&
      !(std::fabs(*settings.elevation_deg) < 90.0))  // also rejects NaN
    throw std::invalid_argument("orbit_camera: elevation must be in (-90, 90) degrees");
  const Eigen::Vector3d offset = base.eye - base.target;
  const double distance_m = offset.norm();
  if (!(distance_m > 0.0) || !std::isfinite(distance_m))
    throw std::invalid_argument("orbit_camera: the base camera's eye and target coincide");

  // Offset = distance·(cos e·h + sin e·z), h the unit horizontal direction.
  Eigen::Vector3d horizontal(offset.x(), offset.y(), 0.0);
  const bool vertical = horizontal.norm() <= 1e-12 * distance_m;
  horizontal = vertical ? Eigen::Vector3d(0.0, -1.0, 0.0) : horizontal.normalized();
  const double elevation_rad = settings.elevation_deg ? *settings.elevation_deg * base::kPi / 180.0
                                                      : std::asin(offset.z() / distance_m);
  // Without an elevation override and with a horizontal offset, keep the base offset's exact
  // direction (frame 0 reproduces the base eye bit for bit up to the rotation by zero).
  Eigen::Vector3d direction =
      settings.elevation_deg || vertical
          ? Eigen::Vector3d(std::cos(elevation_rad) * horizontal +
                            std::sin(elevation_rad) * Eigen::Vector3d::UnitZ())
          : Eigen::Vector3d(offset / distance_m);

  const double azimuth_rad = orbit_azimuth_deg(i, n) * base::kPi / 180.0;
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(azimuth_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  render::Camera camera = base;
  // The orbit is a look-at path: a calibrated base camera lends it its position, view axis,
  // up (its −y axis) and vertical field of view (render/camera.h), not its intrinsics.
  camera.intrinsics.reset();
  camera.target = center_m;
  camera.eye = center_m + turn * direction * (distance_m * settings.distance_scale);
  camera.up = turn * base.up;
  return camera;
}

}  // namespace weft::app
