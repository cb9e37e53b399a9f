#pragma once
// The meeting point of sim and render for obstacles: each analytic obstacle as a RenderObject.

#include <vector>

#include "render/render_settings.h"
#include "sim/collision/obstacle.h"
#include "sim/collision/obstacle_motion.h"

namespace weft::app {

// Half the side of the square drawn for a plane obstacle that is not the rendered ground, m.
inline constexpr double plane_patch_half_size_m = 2.0;

// One RenderObject per obstacle to draw, in settings.obstacle_color:
// - a sphere: a sphere mesh at its true radius (the cloth rests collision_thickness outside it);
// - a box, cylinder or capsule: its closed mesh at its true size (render/primitives.h);
// - a mesh: its own triangles, posed, each corner's normal averaged over the triangles around
//   its vertex within mesh_crease_angle_deg of its own (smooth, but sharp edges stay sharp);
// - a plane: a 4 m × 4 m square centred on the point of the plane nearest the camera target,
//   facing along its normal; none when the plane is the rendered ground (settings.ground on,
//   normal +z and height ground_z_m, within 1e-9), which already shows it.
std::vector<render::RenderObject> obstacle_render_objects(
    const std::vector<sim::Obstacle>& obstacles, const render::RenderSettings& settings);
// The same for the obstacles where their motions (empty, or one per obstacle) put them at time_s.
std::vector<render::RenderObject> obstacle_render_objects(
    const std::vector<sim::Obstacle>& obstacles, const std::vector<sim::ObstacleMotion>& motions,
    double time_s, const render::RenderSettings& settings);

inline constexpr double mesh_crease_angle_deg = 30.0;

}  // namespace weft::app
