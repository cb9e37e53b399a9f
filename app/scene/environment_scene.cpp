// Scene keys of image-based lighting (environment_scene.h).

#include "app/scene/environment_scene.h"
#include "app/scene/scene_inputs.h"

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

namespace weft::app {

void read_environment(ObjectReader& render, render::Environment& environment) {
  if (!render.has("environment")) return;
  ObjectReader r = render.object("environment");
  const std::filesystem::path file = r.string("file", required);
  const std::filesystem::path path = scene_relative(r.file(), file);
  try {
    environment.map =
        std::make_shared<const render::EnvironmentMap>(render::read_environment_map(path));
  } catch (const std::exception& e) {
    r.fail("file", "expected an equirectangular Radiance .hdr map: " + std::string(e.what()));
  }
  environment.rotation_deg = r.angle_deg("rotation", environment.rotation_deg);
  environment.intensity = r.number("intensity", environment.intensity, Range::ge(0.0));
  environment.background = r.boolean("background", environment.background);
  r.finish();
}

}  // namespace weft::app
