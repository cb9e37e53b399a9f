// The `weft` command.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/measure_command.h"
#include "app/run_command.h"
#include "app/scene.h"
#include "app/stability_command.h"
#include "app/sweep_command.h"
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
      ->check(CLI::IsMember({"raster", "raytrace"}));
  int samples = 0;
  run_cmd->add_option("--samples", samples,
                      "Ray tracer samples per pixel (overrides render.raytrace.samples)");
  run_cmd->add_flag("--explain", run.explain,
                    "Print the terms and phases the simulation runs, and each phase's share of its time");

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

  if (argc == 1) {  // no command: say what there is
    std::fputs(app.help().c_str(), stdout);
    return exit_bad_input;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "weft: error: %s (see weft --help)\n", e.what());
    return exit_bad_input;
  }

  try {
    if (run_cmd->parsed()) {
      if (!scene_path.empty()) run.scene = scene_path;
      if (!out_dir.empty()) run.out = out_dir;
      if (run_cmd->count("--frames")) run.frames = frames;
      if (!size.empty()) run.size = size;
      if (!shading.empty()) run.normals_shading = shading == "normals";
      if (!renderer.empty()) run.renderer = renderer;
      if (run_cmd->count("--samples")) run.samples = samples;
      return run_scene(run);
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
