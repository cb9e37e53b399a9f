#pragma once
// Private to render/: GLSL 3.30 core sources of the rasterizer's programs.
//
// Colour convention (all programs): settings colours are used as given, and the lighting term
// is gamma-encoded before it scales them:
//   colour = base × (ambient + intensity × max(0, n·l))^(1/2.2)
// so an unlit surface shows ambient^(1/2.2) of its colour and a fully lit one about its colour.
// Under an environment map the ambient term gives way to the map's 9-coefficient spherical-
// harmonic irradiance / π (per RGB channel; render/environment.h), evaluated at the normal.

#include <string>

namespace weft::render::detail {

// Cloth: per-vertex normals; front faces (counter-clockwise on screen) use u_front_color, back
// faces u_back_color with the normal flipped. u_shading 0 = lit, 1 = normals (0.5 n + 0.5).
extern const char* const cloth_vertex_shader;
extern const char* const cloth_fragment_shader;

// Ground: a square at z = ground_z drawn from gl_VertexID (no vertex buffer), lit by the same
// light, with a procedural 10 cm / 1 m grid, the cloth's shadow and a fade into the background.
extern const char* const ground_vertex_shader;
extern const char* const ground_fragment_shader;
// ground_fragment_shader, or (shadowed false) the same without the shadow lookup: the light
// reaches every pixel, as where the shadow map holds no caster near.
std::string ground_fragment_source(bool shadowed);

// Environment background (render/environment.h): the map seen along each pixel's ray,
// intensity × texel (nearest), encoded as the ray tracer encodes radiance, min(L, 1)^(1/2.2).
// One triangle from gl_VertexID over the viewport.
extern const char* const environment_vertex_shader;
extern const char* const environment_fragment_shader;

// Shadow pass: depth only, cloth positions through the light's orthographic view-projection.
extern const char* const shadow_vertex_shader;
extern const char* const shadow_fragment_shader;

}  // namespace weft::render::detail
