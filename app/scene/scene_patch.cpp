// `--set KEY=V1,V2,…` parsing and patching a scene's JSON at a dotted key path.

#include "app/scene/scene_patch.h"

#include <cctype>
#include <set>
#include <utility>

namespace weft::app {

namespace {

std::string option_text(const Setting& s) {
  return s.option.empty() ? "--set " + s.key + "=" + s.value : s.option;
}

[[noreturn]] void bad_option(const std::string& text, const std::string& what) {
  throw InputError("--set '" + text + "': " + what);
}

// One step of a key path: an object key, optionally followed by [k] into an array.
struct PathPart {
  std::string name;
  std::vector<std::size_t> indices;
};

std::vector<PathPart> split_key(const std::string& key, const std::string& option) {
  std::vector<PathPart> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    PathPart p;
    const std::size_t bracket = part.find('[');
    p.name = part.substr(0, bracket);
    if (p.name.empty()) bad_option(option, "expected a dotted key such as cloth.resolution");
    for (std::size_t i = bracket; i != std::string::npos && i < part.size();) {
      const std::size_t close = part.find(']', i);
      const std::string digits =
          close == std::string::npos ? "" : part.substr(i + 1, close - i - 1);
      if (part[i] != '[' || digits.empty() ||
          digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6) {
        bad_option(option, "expected an array index such as obstacles[0] in '" + part + "'");
      }
      p.indices.push_back(static_cast<std::size_t>(std::stoul(digits)));
      i = close + 1;
    }
    parts.push_back(std::move(p));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

// Splits at commas that are outside [], {} and "…".
std::vector<std::string> split_values(const std::string& text, const std::string& option) {
  std::vector<std::string> values;
  std::string current;
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\' && i + 1 < text.size()) {
        current += c;
        current += text[++i];
        continue;
      }
      if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (--depth < 0) bad_option(option, "unbalanced '" + std::string(1, c) + "'");
    } else if (c == ',' && depth == 0) {
      values.push_back(current);
      current.clear();
      continue;
    }
    current += c;
  }
  if (in_string || depth != 0) bad_option(option, "unbalanced brackets or quotes in the values");
  values.push_back(current);
  for (std::string& v : values) {
    const auto first = v.find_first_not_of(" \t");
    const auto last = v.find_last_not_of(" \t");
    v = first == std::string::npos ? "" : v.substr(first, last - first + 1);
    if (v.empty()) bad_option(option, "expected a non-empty value between commas");
  }
  return values;
}

}  // namespace

SettingValues parse_set_option(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    bad_option(text, "expected KEY=VALUE[,VALUE...], e.g. cloth.resolution=[21,21],[41,41]");
  SettingValues option;
  option.key = text.substr(0, eq);
  split_key(option.key, text);  // checks the key's form
  option.values = split_values(text.substr(eq + 1), text);
  std::set<std::string> seen;
  for (const std::string& v : option.values) {
    if (!seen.insert(v).second) bad_option(text, "value '" + v + "' is given twice");
  }
  return option;
}

Json setting_json(const std::string& value) {
  try {
    return parse_json(value, "--set");  // strict, and bounded in depth
  } catch (const InputError&) {
    return Json(value);
  }
}

Json patch_document(Json document, const std::vector<Setting>& settings) {
  for (const Setting& s : settings) {
    const std::vector<PathPart> parts = split_key(s.key, option_text(s));
    Json* node = &document;
    Json* parent = nullptr;
    std::string path;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const PathPart& part = parts[k];
      if (!node->is_object()) {
        bad_option(option_text(s), "'" + path + "' is not an object in the scene, so it has no key '" +
                                       part.name + "'");
      }
      path += (path.empty() ? "" : ".") + part.name;
      parent = node;
      node = &(*node)[part.name];  // creates a missing key (null), filled below
      for (std::size_t index : part.indices) {
        if (!node->is_array() || index >= node->size()) {
          bad_option(option_text(s), "'" + path + "' has no element [" + std::to_string(index) +
                                         "] in the scene");
        }
        path += "[" + std::to_string(index) + "]";
        node = &(*node)[index];
      }
      if (k + 1 < parts.size() && node->is_null()) *node = Json::object();
    }
    Json value = setting_json(s.value);
    // null removes the key (a scene value is never null): e.g. a material's bend_warp that a
    // bending law set beside it would contradict.
    if (value.is_null() && parts.back().indices.empty()) parent->erase(parts.back().name);
    else *node = std::move(value);
  }
  return document;
}

Scene patched_scene(const Scene& base, const std::vector<Setting>& settings) {
  const Json document = patch_document(parse_json(base.text, base.source), settings);
  try {
    Scene scene = parse_scene(document.dump(2) + "\n", base.source);
    scene.name = base.name;
    return scene;
  } catch (const InputError& e) {
    // Name the settings whose key the message mentions; all of them when none does (a
    // combination of values, e.g. a pin outside a coarser grid).
    const std::string message = e.what();
    std::string named;
    for (const Setting& s : settings) {
      if (message.find(": " + s.key) != std::string::npos)
        named += (named.empty() ? "" : ", ") + option_text(s);
    }
    if (named.empty()) {
      for (const Setting& s : settings) named += (named.empty() ? "" : ", ") + option_text(s);
    }
    throw InputError(named + ": " + message);
  }
}

std::vector<std::vector<Setting>> setting_grid(const std::vector<SettingValues>& options) {
  std::set<std::string> keys;
  for (const SettingValues& o : options) {
    if (!keys.insert(o.key).second) throw InputError("--set: key '" + o.key + "' is given twice");
  }
  std::vector<std::vector<Setting>> grid{{}};
  for (const SettingValues& o : options) {
    std::vector<std::vector<Setting>> next;
    for (const std::vector<Setting>& row : grid) {
      for (const std::string& v : o.values) {
        next.push_back(row);
        next.back().push_back({o.key, v, ""});
      }
    }
    grid = std::move(next);
  }
  return grid;
}

std::string describe(const std::vector<Setting>& settings) {
  std::string text;
  for (const Setting& s : settings) text += (text.empty() ? "" : " ") + s.key + "=" + s.value;
  return text;
}

Scene load_scene_with(const std::optional<std::filesystem::path>& path,
                      const std::vector<Setting>& overrides) {
  Scene scene = path ? load_scene(*path) : default_scene();
  if (!overrides.empty()) scene = patched_scene(scene, overrides);
  // An option that only the ray tracer reads does nothing with the rasterizer: say so.
  for (const Setting& s : overrides) {
    if (!s.option.empty() && s.key.rfind("render.raytrace.", 0) == 0 &&
        scene.render.renderer == render::RendererKind::raster)
      scene.warnings.push_back(s.option + ": the raster renderer ignores it (" + s.key +
                               " is the ray tracer's; add --renderer raytrace)");
  }
  for (const std::string& warning : scene.warnings)
    std::fprintf(stderr, "weft: warning: %s\n", warning.c_str());
  return scene;
}

}  // namespace weft::app
