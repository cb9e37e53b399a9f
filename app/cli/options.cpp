// The options shared by the subcommands (see options.h).

#include "app/cli/options.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <regex>

#include "render/render_settings.h"

namespace weft::app {

void add_set_option(CLI::App& command, std::vector<Setting>& overrides) {
  command
      .add_option_function<std::vector<std::string>>(
          "--set",
          [&overrides](const std::vector<std::string>& texts) {
            for (const std::string& text : texts) {
              const SettingValues option = parse_set_option(text);
              if (option.values.size() != 1)
                throw InputError("--set '" + text +
                                 "': expected one value (weft sweep tries several)");
              overrides.push_back({option.key, option.values.front(), ""});
            }
          },
          "KEY=VALUE: set a scene key (dotted path, e.g. simulation.time_step=1ms or "
          "cloth.resolution=[21,21]; the value is JSON or plain text); repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

void add_override_option(CLI::App& command, const std::string& option, const std::string& key,
                         std::vector<Setting>& overrides, const std::string& help,
                         const std::string& type) {
  command
      .add_option_function<std::string>(
          option,
          [&overrides, option, key](const std::string& value) {
            overrides.push_back({key, value, option + " " + value});
          },
          help)
      ->type_name(type);
}

void add_size_option(CLI::App& command, std::vector<Setting>& overrides,
                     const std::string& help) {
  command.add_option_function<std::string>(
      "--size",
      [&overrides](const std::string& text) {
        static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
        std::smatch m;
        if (!std::regex_match(text, m, pattern))
          throw InputError("--size: expected WIDTHxHEIGHT (e.g. 640x480), got '" + text + "'");
        overrides.push_back({"render.size", "[" + m[1].str() + "," + m[2].str() + "]",
                             "--size " + text});
      },
      help);
}

void add_render_options(CLI::App& command, std::vector<Setting>& overrides) {
  add_override_option(command, "--shading", "render.shading", overrides,
                      "lit; normals: the normal as colour; strain: the cloth in false colour by its "
                      "strain, with a legend (±5 %; --set render.strain_scale=0.01 for ±1 %) "
                      "(overrides render.shading)");
  command.get_option("--shading")->check(CLI::IsMember(base::enum_name_list(render::shading_names)));
  add_override_option(command, "--renderer", "render.renderer", overrides,
                      "raster (OSMesa, fast previews) or raytrace (Embree: soft shadows, ambient "
                      "occlusion, sheen; overrides render.renderer)");
  command.get_option("--renderer")->check(CLI::IsMember(render::renderer_choices()));
  add_override_option(command, "--samples", "render.raytrace.samples", overrides,
                      "Ray tracer samples per pixel, the most with adaptive sampling (overrides "
                      "render.raytrace.samples)",
                      "INT");
  add_override_option(command, "--denoise", "render.raytrace.denoise", overrides,
                      "on (the default) or off: the ray tracer's edge-aware denoiser (overrides "
                      "render.raytrace.denoise)", "on|off");
  command.get_option("--denoise")->transform(
      CLI::Transformer(std::map<std::string, std::string>{{"on", "true"}, {"off", "false"}})
          .description(""));
  add_background_option(command, overrides);
}

void add_background_option(CLI::App& command, std::vector<Setting>& overrides) {
  command
      .add_option_function<std::string>(
          "--background",
          [&overrides](const std::string& text) {
            static const std::regex colour(R"(\s*([^,\s]+)\s*,\s*([^,\s]+)\s*,\s*([^,\s]+)\s*)");
            std::smatch m;
            if (text == "transparent")
              overrides.push_back({"output.alpha", "true", "--background " + text});
            else if (std::regex_match(text, m, colour))
              overrides.push_back({"render.colors.background",
                                   "[" + m[1].str() + "," + m[2].str() + "," + m[3].str() + "]",
                                   "--background " + text});
            else
              throw InputError("--background: expected 'transparent' or a colour R,G,B (each "
                               "0..1, e.g. 1,1,1), got '" + text + "'");
          },
          "transparent: RGBA frames, alpha 0 where no surface is seen (≡ --set output.alpha=true); "
          "or R,G,B in 0..1: the background colour (overrides render.colors.background)")
      ->type_name("transparent|R,G,B");
}

void add_threads_option(CLI::App& command, std::optional<int>& threads) {
  command
      .add_option_function<int>(
          "--threads", [&threads](const int& n) { threads = n; },
          "Threads of the ray tracer, self-collision and implicit Euler's conjugate gradients "
          "(0: all hardware threads, the default); the output is the same whatever the number")
      ->check(CLI::Range(0, 4096));  // (an int: CLI11 rejects NaN and fractions itself)
}

std::pair<int, int> parse_size(const std::string& text, const std::string& option) {
  static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (std::regex_match(text, m, pattern)) {
    const int w = std::stoi(m[1]), h = std::stoi(m[2]);
    if (w >= 16 && w <= 8192 && h >= 16 && h <= 8192) return {w, h};
  }
  throw InputError(option +
                   ": expected WIDTHxHEIGHT with each side in 16..8192 (e.g. 640x480), got '" +
                   text + "'");
}

CLI::Option* add_slurm_flags(CLI::App& command, bool& slurm, bool& dry_run, const std::string& help) {
  CLI::Option* flag = command.add_flag("--slurm", slurm, help);
  command.add_flag("--dry-run", dry_run, "With --slurm: write and print the scripts, submit nothing")
      ->needs(flag);
  return flag;
}

}  // namespace weft::app
