#pragma once
// The command-line options that change a scene, shared by the subcommands: each is a scene
// patch through the --set machinery (app/scene_patch.h) — `--samples 64` ≡
// `--set render.raytrace.samples=64` — so the scene reader validates it once (an error names
// the option and the key) and the scene.json copied into the output holds it. And --threads.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/scene.h"
#include "app/scene_patch.h"

namespace CLI {
class App;
}

namespace weft::app {

// The scene file (or the built-in default scene) with the overrides applied through
// patched_scene (none: the file as it is, its text unchanged). Prints the scene's warnings
// ("weft: warning: …") to stderr.
Scene load_scene_with(const std::optional<std::filesystem::path>& path,
                      const std::vector<Setting>& overrides);

// --set KEY=VALUE, repeatable: one scene key each (weft run, measure, turntable).
void add_set_option(CLI::App& command, std::vector<Setting>& overrides);

// An option that overrides one scene key: `--frames 24` ≡ `--set output.frames=24`. The value
// is passed on as typed and checked by the scene reader; an error names the option and key.
// `type` is the value's name in --help (e.g. "INT").
void add_override_option(CLI::App& command, const std::string& option, const std::string& key,
                         std::vector<Setting>& overrides, const std::string& help,
                         const std::string& type = "TEXT");

// --size WIDTHxHEIGHT ≡ --set render.size=[WIDTH,HEIGHT].
void add_size_option(CLI::App& command, std::vector<Setting>& overrides, const std::string& help);

// --shading, --renderer, --samples and --background: the render overrides of run and turntable.
void add_render_options(CLI::App& command, std::vector<Setting>& overrides);

// --background transparent (≡ --set output.alpha=true: RGBA frames) or R,G,B
// (≡ --set render.colors.background=[R,G,B]).
void add_background_option(CLI::App& command, std::vector<Setting>& overrides);

// --threads N: threads of the ray tracer and of self-collision's candidate search (0: all
// hardware threads; never changes a bit of the output). Checked to be in 0..4096.
void add_threads_option(CLI::App& command, std::optional<int>& threads);
void apply_threads(Scene& scene, std::optional<int> threads);

}  // namespace weft::app
