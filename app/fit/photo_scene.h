#pragma once
// A scene from a photo of a cloth held by two corners (weft photo-scene, docs/photos.md "A
// scene from a photo"): the photo's calibrated camera, its cloth mask and the cloth's size are
// enough — no template mesh.
//
// The scene's world is the camera's OpenCV frame (x right, y down, z forward, metres; the
// camera at the origin looking along +z), as assets/scenes/phi_sft_R1_hang.json.
//
// 1. The held corners' pixels: render/photo_compare/held_corners.h (top-left, top-right).
// 2. Their depth from the cloth's width W (pinhole): each corner lies on its pixel's ray,
//    p = Z (x', y', 1) with x' = (u − cx)/fx, y' = (v − cy)/fy; at one depth Z the corners are
//    Z |(x'₁ − x'₀, y'₁ − y'₀)| apart, so Z₀ = W / |(Δx', Δy')| puts them W apart (a cloth held
//    taut enough that its top edge is straight, unstretched).
// 3. A Placement refines that: the corners' pixels may move by up to a few pixels,
//    depth_scale s multiplies both depths (s > 1: farther and the
//    top edge stretched to s·W), depth_difference d moves the right corner d farther and the
//    left d nearer by halves (Z = s Z₀ ∓ d/2: a cloth turned about the vertical), and tilt θ
//    is the camera's pitch (looking down by θ): gravity in the camera frame is
//    9.81 (0, cos θ, sin θ) m/s². The camera is assumed not rolled.
// 4. The scene: the W × H cloth starts flat in the plane through the two corners and gravity,
//    hanging from them, warp from the left corner to the right, weft up, so its front
//    (warp × weft) faces the camera; the left corner (u0v1) is pinned where it is, the right
//    one (u1v1) starts W from it and a pin path draws it to its place in the first 0.05 s.
//    Mass-spring model, settled by dynamic relaxation (the static equilibrium).

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/camera.h"
#include "render/image.h"
#include "render/mask.h"

namespace weft::app {

// A photo's calibrated pinhole (its intrinsics; the scene's world is its frame) from a JSON
// file, one of:
// - a weft camera object {"intrinsics": {"fx", "fy", "cx", "cy", "size": [W, H]}} (docs/scene.md,
//   render.camera), or a scene file whose render.camera has intrinsics; a pose, if any, must be
//   the identity at the origin;
// - a φ-SfT scene file (R1_scene.json): "focal_lengths" [[a, b]], "optical_centers" [[c, d]]
//   and "image_size" [rows, columns], whose pairs are (row, column): fx = b, fy = a, cx = d,
//   cy = c (docs/photos.md checks it by projecting the point cloud); its camera must be at the
//   origin looking along +z.
// Throws InputError naming the file and key.
render::PinholeIntrinsics read_photo_camera(const std::filesystem::path& path);

struct PhotoSceneSetup {
  render::PinholeIntrinsics camera;  // as given; scaled to the photo's size where used
  int width_px = 0, height_px = 0;   // the photo's (and the scene's render.size)
  double cloth_width_m = 0.0, cloth_height_m = 0.0;
  std::array<int, 2> resolution{32, 32};
  std::string material_preset;                // empty: weft's defaults (wool_kang_yu)
  std::array<Eigen::Vector2d, 2> corners_px;  // top-left, top-right, in the photo's pixels
};

struct Placement {
  // Moves of the held corners' pixels from those found in the mask (a corner pixel lies up to a
  // pixel inside the cloth's true corner, more where fibres or keying blur it).
  std::array<Eigen::Vector2d, 2> corner_shift_px{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  double depth_scale = 1.0;
  double depth_difference_m = 0.0;
  double tilt_rad = 0.0;
  std::optional<double> density_kg_m2;  // none: the preset's (or the default) density
};

// Z₀ of step 2 (m), for the found corners moved by `shift_px`.
double depth_from_width(const PhotoSceneSetup& setup,
                        const std::array<Eigen::Vector2d, 2>& shift_px = {Eigen::Vector2d::Zero(),
                                                                          Eigen::Vector2d::Zero()});
// The held corners' positions (camera frame, m) for a placement: left, right.
std::array<Eigen::Vector3d, 2> held_corner_positions(const PhotoSceneSetup& setup,
                                                     const Placement& p);

// The runnable scene (step 4) as JSON; `texture_file`, when not empty, is set as
// render.texture {file, scale: [W, H]} (one repeat spans the piece). `description` goes into the
// scene's "description".
nlohmann::json photo_scene_json(const PhotoSceneSetup& setup, const Placement& p,
                                const std::string& description,
                                const std::string& texture_file = "");

}  // namespace weft::app
