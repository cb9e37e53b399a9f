#pragma once
// The command-line options shared by the subcommands. Those that change a scene are scene
// patches through the --set machinery (app/scene/scene_patch.h) — `--samples 64` ≡
// `--set render.raytrace.samples=64` — so the scene reader validates them once (an error names
// the option and the key) and the scene.json copied into the output holds them. And
// --threads, --size for commands without a scene, --slurm and --dry-run.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/scene.h"
#include "app/scene/scene_patch.h"

namespace CLI {
class App;
class Option;
}

namespace weft::app {

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

// Parses "640x480" (each side 16..8192); throws InputError naming the option.
std::pair<int, int> parse_size(const std::string& text, const std::string& option);


// Adds --slurm (with `help`) and --dry-run (which needs it) to a command; returns --slurm.
CLI::Option* add_slurm_flags(CLI::App& command, bool& slurm, bool& dry_run, const std::string& help);

}  // namespace weft::app
