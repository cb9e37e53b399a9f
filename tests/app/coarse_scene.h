#pragma once
// A scene file of assets/scenes on a coarser grid, for tests that must run in seconds: the
// grid gets n × n vertices (a disc with a smooth edge ⌊n/2⌋ rings) and a grid-vertex pin moves
// to the same place on it.

#include <cmath>
#include <filesystem>
#include <string>
#include <variant>

#include "app/scene/scene.h"

namespace weft::app::test {

// assets/scenes/<name> as it is.
inline Scene scene_file(const std::string& name) {
  return load_scene(std::filesystem::path(WEFT_SOURCE_DIR) / "assets" / "scenes" / name);
}

inline Scene coarse_scene(const std::string& name, sim::Index n) {
  Scene scene = scene_file(name);
  const auto rescale = [n](sim::Index i, sim::Index count) {
    return static_cast<sim::Index>(std::lround(double(i) * double(n - 1) / double(count - 1)));
  };
  for (sim::PinSpec& pin : scene.pins) {
    if (auto* g = std::get_if<sim::PinGrid>(&pin)) {
      g->i = rescale(g->i, scene.grid.nu);
      g->j = rescale(g->j, scene.grid.nv);
    }
  }
  scene.grid.nu = scene.grid.nv = n;
  return scene;
}

}  // namespace weft::app::test
