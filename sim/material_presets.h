#pragma once
// Named fabrics: a name → Material lookup for scene files ("cloth.material.preset") and tests.
// Each preset says where its numbers come from, and which of them are not from that source;
// docs/scene.md lists them with their sources.

#include <string>
#include <vector>

#include "sim/material.h"

namespace weft::sim {

struct MaterialPreset {
  std::string name;    // e.g. "wool_kang_yu"
  Material material;   // SI units
  std::string source;  // the publication (and table) the numbers come from
  // The Material fields that are NOT from `source` but representative values chosen by weft
  // (e.g. "bend_warp, bend_weft"); empty when every field is published. `source` says why.
  std::string representative_fields;
};

// All presets, in a fixed order (the first is sim::Material's default).
const std::vector<MaterialPreset>& material_presets();

// Their names, in the same order.
std::vector<std::string> material_preset_names();

// The preset called `name`. Throws std::invalid_argument naming it and listing the known names:
// "unknown material preset 'wool' (known: wool_kang_yu, cotton_shirting, ...)".
const MaterialPreset& material_preset(const std::string& name);

}  // namespace weft::sim
