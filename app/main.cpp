// The `weft` command.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <sstream>

#include "app/compare_command.h"
#include "app/diff_command.h"
#include "app/folds_command.h"
#include "app/gallery_command.h"
#include "app/measure_command.h"
#include "app/run_command.h"
#include "app/scene.h"
#include "app/stability_command.h"
#include "app/sweep_command.h"
#include "app/turntable_command.h"
#include "app/version.h"

namespace {

std::string joined(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace weft::app;
  CLI::App app{"weft: offline cloth simulation and visualization.\n"
               "Simulates a scene file and writes a PNG sequence, stats.csv and a copy of the scene."};
  app.set_version_flag("--version", std::string("weft ") + version());
  app.require_subcommand(1);

  RunOptions run;
  run.command_line = joined(argc, argv);
  std::string scene_path, out_dir, size;
  int frames = 0;
  CLI::App* run_cmd = app.add_subcommand("run", "Simulate a scene and write out/<scene>/frame_0001.png, ...");
  run_cmd->add_option("scene", scene_path, "Scene file (JSON, see docs/scene.md); the built-in default scene if omitted");
  run_cmd->add_option("--out", out_dir, "Output folder (default: out/<scene name>)");
  run_cmd->add_option("--frames", frames, "Number of frames to write (overrides output.frames)");
  run_cmd->add_option("--size", size, "Image size WIDTHxHEIGHT (overrides render.size)");
  std::string shading;
  run_cmd->add_option("--shading", shading, "lit, or normals: the normal as colour (overrides render.shading)")
      ->check(CLI::IsMember({"lit", "normals"}));
  std::string renderer;
  run_cmd->add_option("--renderer", renderer,
                      "raster (OSMesa, fast previews) or raytrace (Embree: soft shadows, ambient "
                      "occlusion, sheen; overrides render.renderer)")
      ->check(CLI::IsMember(weft::render::renderer_choices()));
  int samples = 0;
  run_cmd->add_option("--samples", samples,
                      "Ray tracer samples per pixel (overrides render.raytrace.samples)");
  std::string export_meshes;
  run_cmd->add_option("--export-meshes", export_meshes,
                      "Also write each frame's cloth as mesh_0001.obj/.ply/.gltf (assimp; normals, "
                      "UVs = material coordinates in metres)")
      ->check(CLI::IsMember({"obj", "ply", "gltf"}));
  run_cmd->add_flag("--explain", run.explain,
                    "Print the terms and phases the simulation runs, and each phase's share of its time");
  run_cmd->add_flag("--report", run.report,
                    "Also write report.html: contact sheet, last frame, plots of strain, energy and "
                    "time per frame (inline SVG)");

  StabilityOptions stability;
  stability.command_line = run.command_line;
  std::string stability_out;
  std::vector<std::string> stability_integrators;
  CLI::App* stability_cmd = app.add_subcommand(
      "stability", "Sweep time step x stiffness for each integrator; write stability.png/.csv");
  stability_cmd->add_option("--out", stability_out, "Output folder (default: out/stability)");
  stability_cmd->add_option("--size", stability.size, "Vertices per side of the 1 m cloth (default 12)");
  stability_cmd->add_option("--integrators", stability_integrators, "Comma-separated integrators (default: all)")
      ->delimiter(',');
  stability_cmd->add_option("--stiffness-scales", stability.stiffness_scales,
                            "Comma-separated factors on every rigidity (default 0.1,0.3,1,3,10,30,100)")
      ->delimiter(',');
  stability_cmd->add_option("--steps-per-row", stability.steps_per_row,
                            "Time steps h per heatmap row, log spaced (default 24)");

  SweepOptions sweep;
  sweep.command_line = run.command_line;
  std::string sweep_scene, sweep_out;
  int sweep_frames = 0, sweep_reference = 0;
  CLI::App* sweep_cmd = app.add_subcommand(
      "sweep", "Run a scene over a grid of settings; write sweep.csv and sweep.png (error vs wall time)");
  sweep_cmd->add_option("scene", sweep_scene, "Scene file; the built-in default scene if omitted");
  sweep_cmd->add_option("--set", sweep.set,
                        "KEY=V1,V2,...: scene key (dotted path, e.g. cloth.resolution) and the values to "
                        "try (JSON, or plain text such as 1 ms); repeat for a grid of every combination")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sweep_cmd->add_option("--out", sweep_out, "Output folder (default: out/sweep-<scene name>)");
  sweep_cmd->add_option("--frames", sweep_frames, "Frames to simulate in every run (overrides output.frames)");
  sweep_cmd->add_option("--reference", sweep_reference,
                        "Run number (row of sweep.csv) the errors are measured against (default: the "
                        "finished run with the largest wall time, taken as the most accurate)");

  MeasureOptions measure;
  measure.command_line = run.command_line;
  std::string measure_scene_path, measure_out;
  int measure_frames = 0;
  CLI::App* measure_cmd = app.add_subcommand(
      "measure", "Simulate a scene without rendering; print settle time, drape coefficient and "
                 "folds; write measure.csv and outline.csv (docs/measure.md)");
  measure_cmd->add_option("scene", measure_scene_path, "Scene file; the built-in default scene if omitted");
  measure_cmd->add_option("--out", measure_out, "Output folder (default: out/<scene name>)");
  measure_cmd->add_option("--frames", measure_frames, "Frames to simulate (overrides output.frames)");
  measure_cmd->add_flag("--drape", measure.require_drape,
                        "Require the drape measures: an error if no obstacle supports the cloth centre");

  // weft folds (issue 6): tension-field folds of a suspended cloth; inputs converted to SI here.
  FoldsOptions folds;
  folds.command_line = run.command_line;
  double folds_h_cm = 0, folds_L_cm = 0, folds_d_cm = 0, folds_t_mm = 0, folds_E_MPa = 0,
         folds_w_N_mm2 = 0, folds_Q = 0, folds_bottom = 0;
  std::string folds_out, folds_overlay, folds_supports, folds_size, folds_shape = "rectangle",
                        folds_interpolation = "cosine";
  CLI::App* folds_cmd = app.add_subcommand(
      "folds", "Tension-field folds of a cloth hanging from two supports (Conci 2007): print n, Q, "
               "z_max, a_i, L'; render them; draw them on a photo (docs/folds.md)");
  folds_cmd->add_option("--h-cm", folds_h_cm, "Height h of the cloth, cm")->required();
  folds_cmd->add_option("--L-cm", folds_L_cm, "Width L of the flat cloth, cm")->required();
  folds_cmd->add_option("--d-cm", folds_d_cm, "Support displacement d, cm: the span is l = L - d")->required();
  folds_cmd->add_option("--t-mm", folds_t_mm, "Thickness t, mm")->required();
  folds_cmd->add_option("--E-MPa", folds_E_MPa, "Young's modulus E, MPa")->required();
  folds_cmd->add_option("--w-N-mm2", folds_w_N_mm2, "Weight per area w, N/mm^2 (e.g. 15e-7)")->required();
  folds_cmd->add_option("--nu", folds.inputs.poisson_ratio, "Poisson's ratio (default 0.3)");
  folds_cmd->add_option("--c", folds.inputs.load_constant,
                        "Load-condition constant c of eq. (7) (default: the fit to the paper's Table 1)");
  folds_cmd->add_option("--Q", folds_Q, "Amplitude ratio Q > 1, instead of eq. (7)'s");
  folds_cmd->add_option("--tolerance", folds.inputs.tolerance, "On |L' - L|/L (default 0.05)");
  folds_cmd->add_flag("--json", folds.json, "Print the result as one JSON object");
  folds_cmd->add_option("--out", folds_out, "Render the folded cloth to DIR/folds.png (the overlay goes there too; default out/folds)");
  folds_cmd->add_option("--size", folds_size, "Image size WIDTHxHEIGHT of folds.png (default 640x480)");
  folds_cmd->add_option("--shape", folds_shape, "Membrane rendered: rectangle or cosine")
      ->check(CLI::IsMember({"rectangle", "cosine"}));
  folds_cmd->add_option("--interpolation", folds_interpolation,
                        "z between wrinkle lines: cosine (smooth) or linear (the paper's)")
      ->check(CLI::IsMember({"cosine", "linear"}));
  folds_cmd->add_option("--overlay", folds_overlay, "Photo (PNG/JPG) to draw the fold lines on: writes folds_overlay.png");
  folds_cmd->add_option("--supports", folds_supports, "x1,y1,x2,y2: the supports' pixels in the photo");
  folds_cmd->add_option("--bottom", folds_bottom, "Pixel row of the cloth's bottom at the middle (default: same scale as across)");

  // weft turntable (issue 7): the camera orbits a scene's final drape or a mesh file.
  TurntableOptions turntable;
  turntable.command_line = run.command_line;
  std::string turntable_input, turntable_out, turntable_size, turntable_renderer;
  int turntable_samples = 0, turntable_sim_frames = 0;
  double turntable_elevation_deg = 0.0;
  CLI::App* turntable_cmd = app.add_subcommand(
      "turntable", "Orbit the camera around a scene's final drape (or a mesh file): write "
                   "turntable_0001.png, ..., contact_sheet.png, and turntable.mp4/.gif with ffmpeg");
  turntable_cmd->add_option("input", turntable_input,
                            "Scene file (.json; simulated to its last frame first) or mesh file "
                            "(.obj, .ply, .stl, .gltf, .glb, .fbx)")
      ->required();
  turntable_cmd->add_option("--frames", turntable.frames,
                            "Images around the orbit; frame i at azimuth 360*i/N (default 36)");
  turntable_cmd->add_option("--out", turntable_out, "Output folder (default: out/<input name>_turntable)");
  turntable_cmd->add_option("--size", turntable_size, "Image size WIDTHxHEIGHT (overrides render.size)");
  turntable_cmd->add_option("--renderer", turntable_renderer, "raster or raytrace (overrides render.renderer)")
      ->check(CLI::IsMember(weft::render::renderer_choices()));
  turntable_cmd->add_option("--samples", turntable_samples, "Ray tracer samples per pixel");
  turntable_cmd->add_option("--elevation-deg", turntable_elevation_deg,
                            "Camera elevation above the cloth centre, degrees (default: the scene camera's)");
  turntable_cmd->add_option("--distance-scale", turntable.orbit.distance_scale,
                            "Factor on the scene camera's distance to its target (default 1)");
  turntable_cmd->add_option("--sim-frames", turntable_sim_frames,
                            "Simulate to this frame instead of output.frames");

  // weft diff (issue 8): image comparison with explicit thresholds and its own exit codes.
  DiffOptions diff;
  std::string diff_a, diff_b, diff_heatmap;
  CLI::App* diff_cmd = app.add_subcommand(
      "diff", "Compare two images: mean/RMS/max difference, PSNR, SSIM, pixels over a threshold; "
              "exit 0 pass, 1 warn, 2 fail, 3 size mismatch, 4 unreadable file, 5 bad arguments");
  diff_cmd->add_option("a", diff_a, "First image (PNG or JPG)")->required();
  diff_cmd->add_option("b", diff_b, "Second image (PNG or JPG)")->required();
  diff_cmd->add_option("--heatmap", diff_heatmap, "Write a heatmap of the differences to this PNG");
  diff_cmd->add_flag("--json", diff.json, "Print the comparison as one JSON object");
  diff_cmd->add_option("--warn", diff.warn,
                       "Thresholds that warn, e.g. 'psnr<40,ssim<0.99' (metrics: mean, rms, max, "
                       "psnr, ssim, over); repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  diff_cmd->add_option("--fail", diff.fail, "Thresholds that fail, e.g. 'ssim<0.95,over>0.01'; repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  diff_cmd->add_option("--pixel-threshold", diff.pixel_threshold,
                       "A pixel differs when a channel differs by more than this (0..255, default 8)");

  // weft compare (issue 8 item 3): a render against a photo of the real cloth.
  CompareOptions compare;
  std::string compare_photo, compare_render, compare_mask_photo, compare_mask_render,
      compare_transform, compare_out;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare", "Compare a render with a photo: segment both, align, print silhouette IoU, Chamfer "
                 "distance, fold agreement, SSIM; write DIR/overlay.png and DIR/report.html");
  compare_cmd->add_option("photo", compare_photo, "Photo (PNG or JPG, any size)")->required();
  compare_cmd->add_option("render", compare_render, "Render (PNG or JPG; resampled onto the photo)")
      ->required();
  compare_cmd->add_option("--mask-photo", compare_mask_photo,
                          "Mask image of the photo (white = cloth), instead of segmentation");
  compare_cmd->add_option("--mask-render", compare_mask_render,
                          "Mask image of the render (white = cloth), instead of segmentation");
  compare_cmd->add_option("--transform", compare_transform,
                          "s,tx,ty[,deg]: render pixels to photo pixels, p = s R(deg) r + t, "
                          "instead of aligning the silhouettes");
  compare_cmd->add_option("--out", compare_out, "Output folder (default: out/compare)");
  compare_cmd->add_flag("--json", compare.json, "Print the numbers as one JSON object");
  compare_cmd->add_option("--fold-sigma", compare.fold_sigma_px,
                          "Gaussian sigma in photo pixels for the fold maps (default: 1 % of the "
                          "diagonal, at least 1.5)");

  // weft gallery (issue 8 item 4): every scene's final frame and contact sheet, and README.md.
  GalleryOptions gallery;
  gallery.command_line = run.command_line;
  std::string gallery_scenes, gallery_out, gallery_only;
  CLI::App* gallery_cmd = app.add_subcommand(
      "gallery", "Render every scene of assets/scenes into out/gallery: <scene>.png (final frame), "
                 "<scene>_sheet.png (contact sheet), README.md with the commands");
  gallery_cmd->add_option("--scenes", gallery_scenes, "Folder of scene files (default: assets/scenes)");
  gallery_cmd->add_option("--out", gallery_out,
                          "Output folder (default: out/gallery; the repository's gallery/ only if given)");
  gallery_cmd->add_option("--frames-scale", gallery.frames_scale,
                          "Run each scene for this fraction of its frames, e.g. 0.25 for a quick look");
  gallery_cmd->add_option("--only", gallery_only, "Comma-separated scene names (file stems) to render");

  if (argc == 1) {  // no command: say what there is
    std::fputs(app.help().c_str(), stdout);
    return exit_bad_input;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "weft: error: %s (see weft --help)\n", e.what());
    return diff_cmd->parsed() ? int{diff_bad_arguments} : int{exit_bad_input};  // diff: 1 is "warn"
  }

  try {
    if (gallery_cmd->parsed()) {
      if (!gallery_scenes.empty()) gallery.scenes = gallery_scenes;
      if (!gallery_out.empty()) gallery.out = gallery_out;
      std::stringstream names(gallery_only);
      for (std::string name; std::getline(names, name, ',');)
        if (!name.empty()) gallery.only.push_back(name);
      return run_gallery(gallery);
    }
    if (compare_cmd->parsed()) {
      compare.photo = compare_photo;
      compare.render = compare_render;
      if (!compare_mask_photo.empty()) compare.mask_photo = compare_mask_photo;
      if (!compare_mask_render.empty()) compare.mask_render = compare_mask_render;
      if (compare_cmd->count("--transform")) compare.transform = compare_transform;
      if (!compare_out.empty()) compare.out = compare_out;
      return run_compare(compare);
    }
    if (diff_cmd->parsed()) {
      diff.a = diff_a;
      diff.b = diff_b;
      if (!diff_heatmap.empty()) diff.heatmap = diff_heatmap;
      return run_diff(diff);
    }
    if (run_cmd->parsed()) {
      if (!scene_path.empty()) run.scene = scene_path;
      if (!out_dir.empty()) run.out = out_dir;
      if (run_cmd->count("--frames")) run.frames = frames;
      if (!size.empty()) run.size = size;
      if (!shading.empty()) run.normals_shading = shading == "normals";
      if (!renderer.empty()) run.renderer = renderer;
      if (run_cmd->count("--samples")) run.samples = samples;
      if (!export_meshes.empty()) run.export_meshes = parse_mesh_format(export_meshes, "--export-meshes");
      return run_scene(run);
    }
    if (turntable_cmd->parsed()) {
      turntable.input = turntable_input;
      if (!turntable_out.empty()) turntable.out = turntable_out;
      if (!turntable_size.empty()) turntable.size = turntable_size;
      if (!turntable_renderer.empty()) turntable.renderer = turntable_renderer;
      if (turntable_cmd->count("--samples")) turntable.samples = turntable_samples;
      if (turntable_cmd->count("--elevation-deg")) turntable.orbit.elevation_deg = turntable_elevation_deg;
      if (turntable_cmd->count("--sim-frames")) turntable.sim_frames = turntable_sim_frames;
      return run_turntable(turntable);
    }
    if (sweep_cmd->parsed()) {
      if (!sweep_scene.empty()) sweep.scene = sweep_scene;
      if (!sweep_out.empty()) sweep.out = sweep_out;
      if (sweep_cmd->count("--frames")) sweep.frames = sweep_frames;
      if (sweep_cmd->count("--reference")) sweep.reference = sweep_reference;
      return run_sweep(sweep);
    }
    if (measure_cmd->parsed()) {
      if (!measure_scene_path.empty()) measure.scene = measure_scene_path;
      if (!measure_out.empty()) measure.out = measure_out;
      if (measure_cmd->count("--frames")) measure.frames = measure_frames;
      return run_measure(measure);
    }
    if (folds_cmd->parsed()) {
      folds.inputs.height_m = 1e-2 * folds_h_cm;
      folds.inputs.width_m = 1e-2 * folds_L_cm;
      folds.inputs.support_shift_m = 1e-2 * folds_d_cm;
      folds.inputs.thickness_m = 1e-3 * folds_t_mm;
      folds.inputs.youngs_modulus_Pa = 1e6 * folds_E_MPa;
      folds.inputs.weight_N_m2 = 1e6 * folds_w_N_mm2;  // N/mm² → N/m²
      if (folds_cmd->count("--Q")) folds.inputs.ratio = folds_Q;
      if (!folds_out.empty()) folds.out = folds_out;
      if (!folds_size.empty()) folds.size = folds_size;
      if (!folds_overlay.empty()) folds.overlay = folds_overlay;
      if (!folds_supports.empty()) folds.supports = folds_supports;
      if (folds_cmd->count("--bottom")) folds.bottom_px = folds_bottom;
      folds.shape = folds_shape == "cosine" ? weft::sim::MembraneShape::cosine
                                            : weft::sim::MembraneShape::rectangle;
      folds.interpolation = folds_interpolation == "linear" ? weft::sim::FoldInterpolation::linear
                                                            : weft::sim::FoldInterpolation::cosine;
      return run_folds(folds);
    }
    if (stability_cmd->parsed()) {
      if (!stability_out.empty()) stability.out = stability_out;
      if (stability_cmd->count("--integrators"))
        stability.integrators = parse_integrator_list(stability_integrators, "--integrators");
      return run_stability(stability);
    }
  } catch (const SceneError& e) {
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    return exit_failure;
  }
  return exit_ok;
}
