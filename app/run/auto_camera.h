#pragma once
// The camera of a scene that gives none (issue 20 item 3): weft run frames the cloth's bounding
// box over the whole run, so that a cloth that falls, swings or drapes stays in view.

#include <Eigen/Geometry>
#include <optional>

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

// The cloth's bounding box over frames 0..scene.frames of the scene (the frame stream without
// rendering, on a simulator of its own); up to the frame a divergence stops at.
Eigen::AlignedBox3d cloth_bounds_over_run(const Scene& scene);

// Where the scene gives no camera (Scene::camera_given), sets scene.render.camera to the
// framing camera of the cloth over the run (the box `cloth_box_m` when given: weft render's,
// from the saved states) and returns true; otherwise returns false.
bool frame_cloth_if_no_camera(Scene& scene,
                              const std::optional<Eigen::AlignedBox3d>& cloth_box_m = {});

}  // namespace weft::app
