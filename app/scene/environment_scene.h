#pragma once
// Image-based lighting in a scene's `render` block (render/environment.h):
//   "environment": {"file": "studio.hdr",   an equirectangular Radiance .hdr (required)
//                   "rotation": angle,      about +z, counter-clockwise seen from above (0)
//                   "intensity": number,    radiance = intensity × the map's values (1), ≥ 0
//                   "background": bool}     camera rays that miss show the map (true)
// The file's path is relative to the scene file; it is read here, so a missing or unreadable
// map is a scene error naming render.environment.file and the file.

#include "app/scene/json_reader.h"
#include "render/environment.h"

namespace weft::app {

// Reads "environment" from the `render` object into `environment` when present. Throws
// InputError.
void read_environment(ObjectReader& render, render::Environment& environment);

}  // namespace weft::app
