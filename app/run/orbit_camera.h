#pragma once
// The turntable's camera path (weft turntable): the camera orbits a vertical axis (world z)
// through a centre, at a fixed distance and elevation.

#include <optional>

#include <Eigen/Core>

#include "render/camera.h"

namespace weft::app {

struct OrbitSettings {
  // Elevation of the eye above the horizontal plane through the centre, degrees, in (−90, 90);
  // none: the base camera's (that of base.eye − base.target).
  std::optional<double> elevation_deg;
  double distance_scale = 1.0;  // × |base.eye − base.target|, > 0
};

// Frame i (0-based) of an n-frame orbit: the base camera's offset base.eye − base.target,
// with its elevation and length changed as `settings` says, turned by the azimuth 360°·i/n
// about the world z axis and put at `center_m`, which the camera then looks at; up is the base
// up vector turned the same way; the field of view and clip planes are the base camera's.
// So with the defaults, frame 0 is the base camera moved so that it looks at center_m (the base
// camera itself when base.target = center_m), and every frame has the base distance and
// elevation. A base camera straight above or below the target (no horizontal offset) stays
// there, its view turning with its up vector, unless an elevation is given (then the orbit
// starts on the −y side). Throws std::invalid_argument for n < 1, i outside 0..n−1, a bad elevation or scale,
// or eye = target.
render::Camera orbit_camera(const render::Camera& base, const Eigen::Vector3d& center_m, int i,
                            int n, const OrbitSettings& settings = {});

// The azimuth of frame i of n, degrees: 360·i/n.
double orbit_azimuth_deg(int i, int n);

}  // namespace weft::app
