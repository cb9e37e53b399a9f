#pragma once
// What holds the cloth, drawn (render.supports): the scene's pins and stands as RenderObjects,
// so that a hanging cloth does not float from invisible points.
// - Pinned vertices that form a line (three or more neighbours, each within 1.5 edge lengths
//   of the next, all within a quarter edge length of one segment) are a held edge: a rod
//   along it. A rod within 25° of vertical over a rendered ground reaches down to it: the
//   flag's pole.
// - Any other pinned vertex is held by a clip: a small dark box whose jaws close on it.
// - Pins on an obstacle's surface (within 5 mm, as the centre of a Cusick specimen on its
//   disc) are held by the obstacle and get nothing.
// - A sphere, or a cylinder with a vertical axis (a Cusick disc), that floats above a rendered
//   ground stands on a stem with a round foot.
// All of it in RenderSettings::support_color; nothing when RenderSettings::supports is off.

#include <vector>

#include "render/render_settings.h"
#include "sim/collision/obstacle.h"
#include "sim/grid.h"

namespace weft::app {

// The pins' clips and rods where the cloth's positions x (#V×3, m) put the pinned vertices
// (sorted indices) at one frame; `edge_m` is the cloth's typical edge length at rest (its
// rest edges' median), which sizes them.
std::vector<render::RenderObject> pin_support_objects(const std::vector<sim::Index>& pinned,
                                                      const sim::Matrix3X& x, double edge_m,
                                                      const std::vector<sim::Obstacle>& obstacles,
                                                      const render::RenderSettings& settings);

// The stems and feet under floating spheres and vertical cylinders (see above).
std::vector<render::RenderObject> stand_objects(const std::vector<sim::Obstacle>& obstacles,
                                                const render::RenderSettings& settings);

// The median length of the cloth's rest edges (over its triangles' edges), m.
double median_rest_edge_m(const sim::ClothMesh& mesh);

}  // namespace weft::app
