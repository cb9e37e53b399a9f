#pragma once
// `weft photo-scene PHOTO --mask MASK --camera CAMERA.json --cloth-size WxH`: a runnable scene
// of a cloth held by two corners from one photo of it, with no template (app/fit/photo_scene.h,
// docs/photos.md "A scene from a photo"): finds the held corners in the mask, places them at
// the depth the cloth's width gives, optionally fits their depth, their depth difference, the
// camera's tilt and the cloth's density to the mask's outline, settles the cloth, measures it
// against the mask and writes DIR/scene.json, DIR/render.png, DIR/mask.png, DIR/overlay.png,
// DIR/corners.png, DIR/placement.csv and DIR/summary.json; with --texture also DIR/texture.png
// (the photo projected onto the settled cloth), which the scene uses, and the textured
// render's SSIM and ΔE2000 inside the mask.

#include <filesystem>
#include <optional>
#include <string>

#include "app/cli/command.h"

namespace weft::app {

struct PhotoSceneOptions {
  std::filesystem::path photo, mask, camera;
  std::string cloth_size;       // "0.55x0.55" (metres)
  std::string material_preset;  // empty: the defaults
  std::optional<double> density_kg_m2;
  int resolution = 32;  // vertices along the longer side
  // "none" or a comma list of corners, depth, depth-difference, tilt, density
  std::string fit = "corners,depth,depth-difference,tilt,density";
  int max_evaluations = 100;
  double tilt_deg = 0.0, depth_scale = 1.0, depth_difference_m = 0.0;  // the start
  bool texture = false;
  int texture_size = 512;  // texels along the longer side
  // The same view at another size (e.g. the full-size frame of a downscaled photo), to take the
  // texture from; its mask is --mask scaled to it (nearest pixel).
  std::optional<std::filesystem::path> texture_photo;
  std::filesystem::path out = "out/photo_scene";
  bool json = false;
  std::optional<int> threads;
  std::string command_line;
};

int run_photo_scene(const PhotoSceneOptions& options);

Command register_photo_scene(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
