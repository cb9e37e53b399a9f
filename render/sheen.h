#pragma once
// The cloth's sheen lobe, the same in both renderers: the "Charlie" microfibre sheen of
// Estevez & Kulla 2017 ("Production Friendly Microfacet Sheen BRDF") with Neubelt & Pettineo's
// visibility term, added to the diffuse reflection of the cloth (not of the ground or
// obstacles) with weight ClothSurface::sheen and tinted halfway between white and the
// cloth's reflectance. Fibres standing out of the cloth scatter light forward at grazing
// angles: the lobe brightens the cloth's rim and the slopes of folds seen edge-on.
// The ray tracer evaluates it for the sun, the environment and bounces
// (raytrace/integrator.cpp); the rasterizer for its key light (raster_shaders.cpp, the same
// formulas in GLSL).

#include <Eigen/Core>

namespace weft::render {

// The distribution D(h) (Estevez & Kulla 2017, eq. 2) for cos θ_h = n·h and roughness r in
// (0, 1]: (2 + 1/r) · sin^(1/r) θ_h / (2π); ∫ D cos θ_h dω = 1 over the hemisphere.
float charlie_distribution(float n_dot_h, float roughness);
// Neubelt & Pettineo's visibility for sheen: 1 / (4 (n·l + n·v − n·l · n·v)).
float sheen_visibility(float n_dot_l, float n_dot_v);
// Radiance reflected towards v by a sheen lobe of weight 1 under a sun of radiance-equivalent
// intensity 1 (raytrace/shading.h: irradiance π) from l, all unit vectors on the side of n:
// π · f_sheen(l, v) · n·l with f_sheen = D · V; 0 when l or v is below the surface.
float sheen_response(const Eigen::Vector3f& n, const Eigen::Vector3f& l, const Eigen::Vector3f& v,
                     float roughness);
// The lobe's colour for a cloth of linear reflectance ρ: (1 + ρ) / 2.
inline Eigen::Vector3f sheen_tint(const Eigen::Vector3f& reflectance) {
  return 0.5f * (Eigen::Vector3f::Ones() + reflectance);
}

}  // namespace weft::render
