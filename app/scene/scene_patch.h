#pragma once
// `--set KEY=V1,V2,…`: a scene key (a dotted path such as "cloth.resolution" or
// "simulation.time_step") and the values to try for it, and a scene with one value patched in.
// The patched scene goes through parse_scene(), so every check and message of the scene format
// applies; an error then names the --set option as well as the key.

#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"

namespace weft::app {

struct SettingValues {
  std::string key;                  // dotted key path, e.g. "simulation.constraints.tolerance"
  std::vector<std::string> values;  // as typed, e.g. {"[8,8]", "[12,12]"} or {"1 ms", "auto"}
};

// Parses "KEY=V1,V2,…". Values are split at commas outside brackets, braces and double quotes
// ("cloth.resolution=[8,8],[12,12]" has two values). Throws InputError naming "--set".
SettingValues parse_set_option(const std::string& text);

// A value as JSON: the value itself when it parses as JSON (numbers, arrays, objects, true,
// "quoted strings") read by parse_json(), else the text as a JSON string (so 1 ms or auto need
// no quotes; nor does text that parse_json() rejects, such as nesting beyond its limit).
Json setting_json(const std::string& value);

// One choice of a value for each key.
struct Setting {
  std::string key;
  std::string value;
  std::string option{};  // the command-line option that made it, for messages ("--samples 0");
                         // empty: "--set KEY=VALUE"
};

// `document` with each setting written at its dotted key path; missing objects on the way are
// created. Throws InputError naming the --set option when a part of the path is not an object.
Json patch_document(Json document, const std::vector<Setting>& settings);

// The scene `base` (its text, source and name) with the settings applied, re-read through
// parse_scene(). An invalid key or value throws InputError reading
// "--set KEY=VALUE: FILE: KEY: what was expected …".
Scene patched_scene(const Scene& base, const std::vector<Setting>& settings);

// Every combination of one value per option (the Cartesian product), the last option varying
// fastest. Throws InputError when a key is given twice.
std::vector<std::vector<Setting>> setting_grid(const std::vector<SettingValues>& options);

// "key=value key2=value2", for labels and progress lines.
std::string describe(const std::vector<Setting>& settings);

// The scene file (or the built-in default scene) with the overrides applied through
// patched_scene (none: the file as it is, its text unchanged). Prints the scene's warnings
// ("weft: warning: …") to stderr.
Scene load_scene_with(const std::optional<std::filesystem::path>& path,
                      const std::vector<Setting>& overrides);

}  // namespace weft::app
