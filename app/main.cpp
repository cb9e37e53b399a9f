// The `weft` command.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/run_command.h"
#include "app/scene.h"
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
  run_cmd->add_flag("--explain", run.explain,
                    "Print the terms and phases the simulation runs, and each phase's share of its time");

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
      return run_scene(run);
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
