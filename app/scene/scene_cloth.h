#pragma once
// The `cloth` block of a scene file (docs/scene.md): the warp/weft grid (size, resolution, shape,
// placement, initial_shape) or a mesh file (mesh and its keys, docs/meshes.md), the material and
// the pins.

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"

namespace weft::app {

// Reads `cloth` into scene.grid (or scene.mesh), scene.tension_field, scene.material,
// scene.pins and scene.pin_paths; resolves each pin against the cloth, so that an error names
// its key path, and adds to scene.warnings a vertex pinned twice or a cloth pinned everywhere.
// Throws InputError.
void read_cloth(ObjectReader cloth, Scene& scene);

}  // namespace weft::app
