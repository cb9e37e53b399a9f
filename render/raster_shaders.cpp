// GLSL sources for raster.cpp; see raster_shaders.h for what each program draws.

#include "render/raster_shaders.h"

#include <string>

namespace weft::render::detail {

const char* const cloth_vertex_shader = R"glsl(
#version 330 core
layout(location = 0) in vec3 a_position;  // world, metres
layout(location = 1) in vec3 a_normal;    // world, unit (front side)
layout(location = 2) in vec2 a_uv;        // material coordinates (warp, weft), metres
layout(location = 3) in vec3 a_colour;    // strain false colour (render/strain_colour.h)
uniform mat4 u_view_projection;           // world -> clip
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
out vec3 v_colour;
void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_uv = a_uv;
  v_colour = a_colour;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)glsl";

const char* const cloth_fragment_shader = R"glsl(
#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
in vec3 v_colour;
uniform vec3 u_eye;               // world, metres
uniform vec3 u_light_dir;         // world, unit, towards the key light
uniform float u_light_intensity;  // diffuse key light
uniform float u_ambient;
uniform vec3 u_front_color;
uniform vec3 u_back_color;
uniform int u_shading;            // 0 lit, 1 normals
uniform int u_use_texture;        // 1: the front colour comes from u_texture (render/texture.h)
uniform int u_texture_back;       // 1: and the back colour too
uniform int u_use_vertex_colour;  // 1: both sides take v_colour (the strain false colour)
uniform sampler2D u_texture;      // rows uploaded bottom first: t = 0 is the image's bottom
uniform vec2 u_texture_origin;    // material coordinates (m) of texture coordinates (0, 0)
uniform vec2 u_texture_size;      // metres of material per unit of texture coordinate
uniform int u_use_environment;    // 1: image-based light (render/environment.h) replaces ambient
uniform vec3 u_sh[9];             // its reflected radiance as a polynomial in n (environment.h)
uniform sampler2D u_weave;        // the weave's normal map (render/weave.h), unit 2
uniform vec2 u_weave_repeat;      // metres of material per weave repeat along warp and weft
uniform float u_weave_depth;      // 0: no weave relief
uniform int u_cloth;              // 1: the cloth, with its sheen and weave
uniform float u_sheen;            // the cloth's sheen weight (render/sheen.h); 0: none
uniform float u_sheen_roughness;
out vec4 o_color;

const float PI = 3.14159265358979;

// render/weave.cpp's tilt_normal: n tilted by the weave's normal map, with the tangents along
// the warp and the weft from the screen-space derivatives of position and material coordinates.
vec3 weave_tilted(vec3 n) {
  vec3 dp_dx = dFdx(v_world), dp_dy = dFdy(v_world);
  vec2 duv_dx = dFdx(v_uv), duv_dy = dFdy(v_uv);
  float det = duv_dx.x * duv_dy.y - duv_dx.y * duv_dy.x;
  if (abs(det) < 1e-20) return n;
  vec3 t_warp = (dp_dx * duv_dy.y - dp_dy * duv_dx.y) / det;
  vec3 t_weft = (dp_dy * duv_dx.x - dp_dx * duv_dy.x) / det;
  vec3 t = t_warp - dot(n, t_warp) * n;
  if (length(t) < 1e-12) return n;
  t = normalize(t);
  vec3 b = cross(n, t);
  if (dot(b, t_weft) < 0.0) b = -b;
  vec3 m = 2.0 * texture(u_weave, v_uv / u_weave_repeat).rgb - 1.0;
  m.xy *= u_weave_depth;
  vec3 tilted = m.x * t + m.y * b + m.z * n;
  return length(tilted) > 0.0 ? normalize(tilted) : n;
}

// render/sheen.cpp in GLSL: the Charlie distribution and sheen_response (radiance towards v
// under a unit sun from l, n·l included).
float charlie_distribution(float n_dot_h, float roughness) {
  float inv_r = 1.0 / roughness;
  float sin2 = max(0.0, 1.0 - n_dot_h * n_dot_h);
  return (2.0 + inv_r) * pow(sin2, 0.5 * inv_r) / (2.0 * PI);
}
float sheen_response(vec3 n, vec3 l, vec3 v, float roughness) {
  float n_dot_l = dot(n, l), n_dot_v = dot(n, v);
  if (n_dot_l <= 0.0 || n_dot_v <= 0.0) return 0.0;
  vec3 half_vector = l + v;
  if (length(half_vector) <= 0.0) return 0.0;
  float n_dot_h = dot(n, normalize(half_vector));
  float denominator = 4.0 * (n_dot_l + n_dot_v - n_dot_l * n_dot_v);
  return PI * charlie_distribution(n_dot_h, roughness) / denominator * n_dot_l;
}

// Radiance a white Lambertian surface of normal n reflects under the environment (9 SH terms).
vec3 environment_radiance(vec3 n) {
  return u_sh[0] + u_sh[1] * n.y + u_sh[2] * n.z + u_sh[3] * n.x + u_sh[4] * (n.x * n.y) +
         u_sh[5] * (n.y * n.z) + u_sh[6] * (3.0 * n.z * n.z - 1.0) + u_sh[7] * (n.x * n.z) +
         u_sh[8] * (n.x * n.x - n.y * n.y);
}

void main() {
  // Geometric normal turned towards the eye: the fallback when the interpolated vertex normal
  // vanishes (vertex normals of opposite sign across a sharp fold).
  vec3 geometric = cross(dFdx(v_world), dFdy(v_world));
  geometric = length(geometric) > 0.0 ? normalize(geometric) : vec3(0.0, 0.0, 1.0);
  if (dot(geometric, u_eye - v_world) < 0.0) geometric = -geometric;

  float len = length(v_normal);
  vec3 n = len > 1e-6 ? v_normal / len : geometric;
  if (!gl_FrontFacing && len > 1e-6) n = -n;  // back face: its normal points the other way
  if (u_cloth == 1 && u_weave_depth > 0.0 && u_use_vertex_colour == 0 && u_shading == 0)
    n = weave_tilted(n);
  vec3 base = gl_FrontFacing ? u_front_color : u_back_color;
  if ((gl_FrontFacing || u_texture_back == 1) && u_use_texture == 1)
    base = texture(u_texture, (v_uv - u_texture_origin) / u_texture_size).rgb;
  if (u_use_vertex_colour == 1) base = v_colour;

  if (u_shading == 1) {
    o_color = vec4(0.5 * n + 0.5, 1.0);
    return;
  }
  vec3 lit = u_use_environment == 1
                 ? u_light_intensity * max(dot(n, u_light_dir), 0.0) + environment_radiance(n)
                 : vec3(u_ambient + u_light_intensity * max(dot(n, u_light_dir), 0.0));
  lit = max(lit, vec3(0.0));
  if (u_cloth == 1 && u_sheen > 0.0 && u_use_vertex_colour == 0) {
    // Linear radiance: diffuse ρ · light plus the key light's sheen, tinted (1 + ρ) / 2.
    vec3 rho = pow(base, vec3(2.2));
    float sheen = u_sheen * u_light_intensity *
                  sheen_response(n, u_light_dir, normalize(u_eye - v_world), u_sheen_roughness);
    o_color = vec4(pow(rho * lit + 0.5 * (1.0 + rho) * sheen, vec3(1.0 / 2.2)), 1.0);
    return;
  }
  o_color = vec4(base * pow(lit, vec3(1.0 / 2.2)), 1.0);
}
)glsl";

const char* const ground_vertex_shader = R"glsl(
#version 330 core
uniform mat4 u_view_projection;  // world -> clip
uniform vec3 u_ground_center;    // world, metres; z is the ground height
uniform float u_half_size;       // metres
out vec3 v_world;
void main() {
  // Triangle strip (-,-), (+,-), (-,+), (+,+): counter-clockwise seen from above (+z).
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
  v_world = u_ground_center + vec3(corner * u_half_size, 0.0);
  gl_Position = u_view_projection * vec4(v_world, 1.0);
}
)glsl";

const char* const ground_fragment_shader = R"glsl(
#version 330 core
in vec3 v_world;
uniform vec3 u_ground_center;     // world, metres
uniform float u_half_size;        // metres
uniform vec3 u_ground_color;
uniform vec3 u_background;
uniform vec3 u_light_dir;         // world, unit, towards the key light
uniform float u_light_intensity;
uniform float u_ambient;
uniform int u_shading;            // 0 lit, 1 normals
uniform int u_use_shadow;         // 0: no shadow map bound
uniform mat4 u_shadow_matrix;     // world -> shadow map texture coordinates and depth, [0,1]^3
uniform sampler2DShadow u_shadow_map;
uniform float u_shadow_texel;     // 1 / shadow map size
uniform int u_use_environment;    // 1: image-based light replaces ambient
uniform vec3 u_environment_up;    // the radiance it makes a white ground reflect, seen from +z
uniform vec3 u_environment_down;  // and from −z
uniform int u_blend_rim;          // 1: fade into what is drawn below (the map) by alpha
out vec4 o_color;

// Coverage (0..1) of grid lines every `spacing` metres, about two pixels wide and antialiased;
// faded out where the lines would be closer than a few pixels apart (no moire far away).
float grid(vec2 p, float spacing) {
  vec2 coord = p / spacing;
  vec2 cells_per_pixel = max(fwidth(coord), vec2(1e-6));
  vec2 pixels_to_line = abs(fract(coord + 0.5) - 0.5) / cells_per_pixel;
  float line = 1.0 - clamp(min(pixels_to_line.x, pixels_to_line.y) - 0.5, 0.0, 1.0);
  float fade = 1.0 - smoothstep(0.12, 0.3, max(cells_per_pixel.x, cells_per_pixel.y));
  return line * fade;
}

// Fraction of the key light reaching this point (1 lit, 0 in the cloth's shadow), 5x5 PCF.
// Compiled twice (ground_fragment_source): WEFT_UNSHADOWED leaves the lookup out altogether,
// for the pixels where it would return 1 (llvmpipe runs both sides of a branch, so a uniform
// test alone saves nothing).
float light_visibility() {
#ifdef WEFT_UNSHADOWED
  return 1.0;
#else
  if (u_use_shadow == 0) return 1.0;
  vec3 s = (u_shadow_matrix * vec4(v_world, 1.0)).xyz;
  if (any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0)))) return 1.0;
  // Beyond the far plane is behind every caster; before the near plane in front of all.
  float reference = clamp(s.z, 0.0, 1.0) - 0.002;
  float sum = 0.0;
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) {
      vec2 offset = vec2(float(i), float(j)) * (1.5 * u_shadow_texel);
      sum += textureLod(u_shadow_map, vec3(s.xy + offset, reference), 0.0);
    }
  }
  return sum / 25.0;
#endif
}

void main() {
  vec3 n = gl_FrontFacing ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 0.0, -1.0);
  float lines = max(0.07 * grid(v_world.xy, 0.1), 0.16 * grid(v_world.xy, 1.0));
  if (u_shading == 1) {
    o_color = vec4(0.5 * n + 0.5, 1.0);
    return;
  }
  float diffuse = max(dot(n, u_light_dir), 0.0);
  if (diffuse > 0.0) diffuse *= light_visibility();
  float light = u_ambient + u_light_intensity * diffuse;
  vec3 lit = u_ground_color * (1.0 - lines) * pow(max(light, 0.0), 1.0 / 2.2);
  if (u_use_environment == 1) {
    vec3 sky = gl_FrontFacing ? u_environment_up : u_environment_down;
    vec3 light3 = u_light_intensity * diffuse + sky;
    lit = u_ground_color * (1.0 - lines) * pow(max(light3, vec3(0.0)), vec3(1.0 / 2.2));
  }
  // Fade into the background over the outer 40% of the square's inscribed circle.
  float r = length(v_world.xy - u_ground_center.xy) / u_half_size;
  if (u_blend_rim == 1) {
    o_color = vec4(lit, 1.0 - smoothstep(0.6, 1.0, r));
    return;
  }
  o_color = vec4(mix(lit, u_background, smoothstep(0.6, 1.0, r)), 1.0);
}
)glsl";

const char* const shadow_vertex_shader = R"glsl(
#version 330 core
layout(location = 0) in vec3 a_position;  // world, metres
uniform mat4 u_light_view_projection;     // world -> light clip (orthographic)
void main() { gl_Position = u_light_view_projection * vec4(a_position, 1.0); }
)glsl";

const char* const shadow_fragment_shader = R"glsl(
#version 330 core
void main() {}
)glsl";

const char* const environment_vertex_shader = R"glsl(
#version 330 core
void main() {
  // One triangle over the whole viewport, at the far plane.
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  gl_Position = vec4(corner, 1.0, 1.0);
}
)glsl";

const char* const environment_fragment_shader = R"glsl(
#version 330 core
uniform mat4 u_inverse_view_projection;  // clip -> world
uniform vec2 u_viewport;                 // width, height in pixels
uniform vec2 u_rotation;                 // cos, sin of the map's rotation about +z
uniform float u_intensity;
uniform sampler2D u_map;                 // rows uploaded top first: t = v (render/environment.h)
out vec4 o_color;
void main() {
  vec2 ndc = 2.0 * gl_FragCoord.xy / u_viewport - 1.0;
  vec4 near = u_inverse_view_projection * vec4(ndc, -1.0, 1.0);
  vec4 far = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
  vec3 d = normalize(far.xyz / far.w - near.xyz / near.w);
  // World -> map direction (turned back by the rotation), then the map point (u, v).
  vec3 m = vec3(u_rotation.x * d.x + u_rotation.y * d.y, -u_rotation.y * d.x + u_rotation.x * d.y,
                d.z);
  const float pi = 3.14159265358979;
  vec2 uv = vec2(0.5 - atan(m.y, m.x) / (2.0 * pi), acos(clamp(m.z, -1.0, 1.0)) / pi);
  vec3 radiance = u_intensity * texture(u_map, uv).rgb;
  o_color = vec4(pow(clamp(radiance, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)glsl";

std::string ground_fragment_source(bool shadowed) {
  std::string source = ground_fragment_shader;
  if (!shadowed) {
    const std::string version = "#version 330 core\n";
    source.insert(source.find(version) + version.size(), "#define WEFT_UNSHADOWED\n");
  }
  return source;
}

}  // namespace weft::render::detail
