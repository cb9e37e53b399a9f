#pragma once
// The ray tracer's shading model, as pure functions.
//
// Colours in RenderSettings are what the rasterizer shows at full light: it draws
// colour × light^(1/2.2). The ray tracer therefore takes the reflectance ρ = colour^2.2,
// transports linear radiance L, and writes byte = round(255 · clamp(L, 0, 1)^(1/2.2)). A
// Lambertian surface under the sun and an unoccluded sky then shows
//     colour × (ambient + intensity · max(0, n·l))^(1/2.2),
// the rasterizer's value exactly. Units: the sun's `intensity` is the radiance a white
// Lambertian surface facing it reflects (its irradiance is π · intensity); the sky's radiance
// is `ambient`, uniform over the upper and lower hemispheres.

#include <Eigen/Core>

#include "render/sheen.h"

namespace weft::render::rt {

inline constexpr float display_gamma = 2.2f;

// colour (0..1, as displayed) → linear reflectance, per channel: c^2.2.
Eigen::Vector3f reflectance_from_color(const Eigen::Vector3f& color);
// Linear radiance → 8-bit value: round(255 · clamp(L, 0, 1)^(1/2.2)).
unsigned char encode_channel(float radiance);

// The cloth's sheen lobe (charlie_distribution, sheen_visibility, sheen_response, sheen_tint)
// is shared with the rasterizer: render/sheen.h.

// Darkening (0..1) by the ground's grid lines at ground point (x, y), m, seen with a footprint
// of `pixel_m` metres per pixel: lines every 0.1 m and 1 m, about two pixels wide, the fine
// ones faded where they would be closer than a few pixels (as the rasterizer's ground).
float ground_grid_lines(float x_m, float y_m, float pixel_m);

}  // namespace weft::render::rt
