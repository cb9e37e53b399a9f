#pragma once
// Private to render/: GLSL 3.30 core sources of the rasterizer's programs.
//
// Colour convention (all programs): settings colours are used as given, and the lighting term
// is gamma-encoded before it scales them:
//   colour = base × (ambient + intensity × max(0, n·l))^(1/2.2)
// so an unlit surface shows ambient^(1/2.2) of its colour and a fully lit one about its colour.

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

// Shadow pass: depth only, cloth positions through the light's orthographic view-projection.
extern const char* const shadow_vertex_shader;
extern const char* const shadow_fragment_shader;

}  // namespace weft::render::detail
