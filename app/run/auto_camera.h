#pragma once
// The camera of a scene that gives none: weft run frames the cloth's bounding
// box over the whole run, so that a cloth that falls, swings or drapes stays in view.

#include <Eigen/Geometry>

#include "app/scene/scene.h"
#include "render/camera.h"

namespace weft::app {

// A camera looking at the box's centre along `base`'s view direction (base.eye − base.target),
// with base's up vector and field of view, just far enough back that the box's bounding sphere
// fits the narrower of the vertical and horizontal fields of view (an image width × height),
// with 5 % to spare; the far plane beyond the box. Throws std::invalid_argument for an empty box.
render::Camera framing_camera(const Eigen::AlignedBox3d& box_m, const render::Camera& base,
                              int width, int height);

// Grows the box by the positions x (#V×3, m).
void extend_box(Eigen::AlignedBox3d& box, const sim::Matrix3X& x);

// The cloth's bounding box over frames 0..last_frame of the scene, simulated on a simulator of
// its own (the frame stream without rendering); up to the frame a divergence stops at. For a
// resumed weft run whose earlier frames' states are gone.
Eigen::AlignedBox3d cloth_bounds_over_frames(const Scene& scene, int last_frame);

// Where the scene gives no camera (Scene::camera_given), sets scene.render.camera to the
// framing camera of `cloth_box_m`, the cloth's bounding box over frames 0..scene.frames (or up
// to a divergence): weft run's, grown frame by frame as it simulates; weft render's, from the
// saved states. Returns whether it did.
bool frame_cloth_if_no_camera(Scene& scene, const Eigen::AlignedBox3d& cloth_box_m);

}  // namespace weft::app
