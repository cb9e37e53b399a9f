#include "app/cli/run_command.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "app/cli/options.h"
#include "app/run/run_job.h"
#include "app/scene/json_reader.h"

namespace weft::app {

namespace {

// --rest: one frame, the static solve's rest shape; not with the options about frames in time.
void add_rest_option(CLI::App& cmd, RunOptions& o) {
  CLI::Option* rest = cmd.add_flag(
      "--rest", o.rest,
      "Write one frame: the cloth's rest shape, found by the static equilibrium solver instead of "
      "simulating its motion (simulation.static, docs/measure.md \"Static solves\")");
  for (const char* name : {"--resume", "--checkpoint-every", "--frames", "--start", "--end", "--every",
                           "--last", "--save-states"})
    rest->excludes(cmd.get_option(name));
}

}  // namespace

Command register_run(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<RunOptions>();
  o->command_line = command_line;
  CLI::App* cmd =
      app.add_subcommand("run", "Simulate a scene and write out/<scene>/frame_0001.png, ...");
  cmd->add_option("scene", o->scene,
                  "Scene file (JSON, see docs/scene.md); the built-in default scene if omitted");
  cmd->add_option("--out", o->out, "Output folder (default: out/<scene name>)");
  add_set_option(*cmd, o->overrides);
  add_override_option(*cmd, "--frames", "output.frames", o->overrides,
                      "Number of frames to write (overrides output.frames)", "INT");
  add_size_option(*cmd, o->overrides, "Image size WIDTHxHEIGHT (overrides render.size)");
  add_render_options(*cmd, o->overrides);
  add_threads_option(*cmd, o->threads);
  FrameSelection& f = o->selection;
  CLI::Option* start = check_range(
      cmd->add_option("--start", f.start, "First frame to render and write (default 1)"),
      Range::closed(1, 100000));
  CLI::Option* end = check_range(
      cmd->add_option("--end", f.end, "Last frame to render and write (default: the last)"),
      Range::closed(1, 100000));
  CLI::Option* every = check_range(
      cmd->add_option("--every", f.every, "Render and write every Nth frame from --start, and the last"),
      Range::closed(1, 100000));
  cmd->add_flag("--last", f.last_only,
                "Render and write only the final frame (every frame is still simulated)")
      ->excludes(start)
      ->excludes(end)
      ->excludes(every);
  cmd->add_option_function<std::string>(
         "--export-meshes",
         [o](const std::string& text) {
           o->export_meshes = parse_mesh_format(text, "--export-meshes");
         },
         "Also write each frame's cloth as mesh_0001.obj/.ply/.gltf (assimp; y-up, normals, UVs "
         "= material coordinates in metres, the cloth's colour; a glTF also its texture)")
      ->check(CLI::IsMember({"obj", "ply", "gltf"}));
  cmd->add_option_function<std::string>(
      "--export-cache",
      [o](const std::string& text) { o->export_cache = parse_cache_formats(text, "--export-cache"); },
      "Also write cloth.obj + cloth.mtl (the start, frame 0, in the cloth's colour) and frames "
      "0..N as cloth.pc2 / cloth.mdd point caches and/or an animated cloth.gltf (morph "
      "targets): pc2, mdd, gltf or a list, e.g. pc2,gltf (y up; sample k is frame k; "
      "docs/export.md)");
  cmd->add_option_function<std::string>(
      "--up", [o](const std::string& text) { o->up = parse_up_axis(text, "--up"); },
      "Up axis of the exported OBJ/PLY: y (default; Blender's OBJ import, as glTF) or z (weft's "
      "frame; for Blender's PLY import, which turns no axes)")->check(CLI::IsMember({"y", "z"}));
  cmd->add_flag_callback(
      "--mask", [o] { o->overrides.push_back({"output.mask", "true", "--mask"}); },
      "Also write mask_0001.png, ...: the cloth's mask from the renderer's geometry (white = "
      "cloth not hidden by obstacles or the ground; overrides output.mask)");
  cmd->add_flag_callback(
      "--alpha", [o] { o->overrides.push_back({"output.alpha", "true", "--alpha"}); },
      "Write RGBA frames, the background transparent (overrides output.alpha)");
  check_range(cmd->add_option("--checkpoint-every", o->checkpoint_every,
                              "Write checkpoint.weft into the output folder after every K-th "
                              "frame, replacing the last (docs/checkpoints.md)"),
              Range::closed(1, 100000));
  cmd->add_option("--resume", o->resume,
                  "Go on from the checkpoint in DIR (a folder weft run --checkpoint-every wrote) "
                  "with the same bits as a run that never stopped; its scene is the checkpoint's")
      ->type_name("DIR")
      ->excludes(cmd->get_option("--out"));
  cmd->add_flag("--save-states", o->save_states,
                "Also write every frame's cloth positions as state_0001.npy, ... (and frame 0's), "
                "from which weft render draws frames without simulating (docs/checkpoints.md)");
  add_rest_option(*cmd, *o);
  cmd->add_flag("--explain", o->explain,
                "Print the terms and phases the simulation runs, and each phase's share of its time");
  cmd->add_flag("--report", o->report,
                "Also write report.html: contact sheet, last frame, plots of strain, energy and "
                "time per frame (inline SVG)");
  // The report shows every frame (its contact sheet, the last frame).
  for (const char* name : {"--start", "--end", "--every", "--last"})
    cmd->get_option("--report")->excludes(cmd->get_option(name));
  return {cmd, [o] { return run_scene(*o); }};
}

}  // namespace weft::app
