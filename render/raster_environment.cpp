// The rasterizer's approximation of image-based lighting (raster_passes.h): the map's
// 9-coefficient spherical-harmonic irradiance for the surfaces and the ground, and the map
// itself behind everything.

#include <cmath>
#include <memory>
#include <vector>

#include "base/constants.h"
#include "render/raster_passes.h"
#include "render/raster_shaders.h"

namespace weft::render::detail {

EnvironmentShading environment_shading(const RenderSettings& s) {
  EnvironmentShading e;
  if (!s.environment.map || s.shading != Shading::lit) return e;
  e.on = true;
  e.background = s.environment.background;
  e.polynomial = sh_reflected_polynomial(project_sh(s.environment));
  e.up = sh_polynomial_value(e.polynomial, Eigen::Vector3f::UnitZ());
  e.down = sh_polynomial_value(e.polynomial, -Eigen::Vector3f::UnitZ());
  return e;
}

EnvironmentPass::EnvironmentPass(const GlFunctions& gl)
    : m_gl(gl),
      m_program(gl, environment_vertex_shader, environment_fragment_shader, "environment") {
  m_gl.GenVertexArrays(1, &m_empty_vao);
}

EnvironmentPass::~EnvironmentPass() {
  m_gl.DeleteTextures(1, &m_texture);  // glDelete* ignore the name 0
  m_gl.DeleteVertexArrays(1, &m_empty_vao);
}

void EnvironmentPass::bind_map(const std::shared_ptr<const EnvironmentMap>& map) {
  if (m_texture == 0) m_gl.GenTextures(1, &m_texture);
  m_gl.ActiveTexture(GL_TEXTURE2);
  m_gl.BindTexture(GL_TEXTURE_2D, m_texture);
  if (m_map != map) {
    // Rows in the map's order, top first: GL's t = 0 is the first row, so t = v.
    std::vector<float> texels;
    texels.reserve(static_cast<std::size_t>(map->width()) * map->height() * 3);
    for (int y = 0; y < map->height(); ++y) {
      for (int x = 0; x < map->width(); ++x) {
        for (int c = 0; c < 3; ++c) texels.push_back(map->texel(x, y)[c]);
      }
    }
    m_gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    m_gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, map->width(), map->height(), 0, GL_RGB, GL_FLOAT,
                    texels.data());
    // Nearest texel, as the ray tracer reads the map (environment.h).
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    m_map = map;
  }
  check_gl_error(m_gl, "uploading the environment map");
}

void EnvironmentPass::draw(const RenderSettings& s, const Eigen::Matrix4f& view_projection) {
  bind_map(s.environment.map);
  const double rotation = base::deg_to_rad(s.environment.rotation_deg);
  m_program.use();
  m_program.set("u_inverse_view_projection", Eigen::Matrix4f(view_projection.inverse()));
  m_program.set("u_viewport", Eigen::Vector2f(static_cast<float>(s.width),
                                              static_cast<float>(s.height)));
  m_program.set("u_rotation", Eigen::Vector2f(static_cast<float>(std::cos(rotation)),
                                              static_cast<float>(std::sin(rotation))));
  m_program.set("u_intensity", static_cast<float>(s.environment.intensity));
  m_program.set("u_map", 2);  // texture unit 2
  m_gl.Disable(GL_DEPTH_TEST);
  m_gl.DepthMask(GL_FALSE);
  m_gl.BindVertexArray(m_empty_vao);
  m_gl.DrawArrays(GL_TRIANGLES, 0, 3);
  m_gl.BindVertexArray(0);
  m_gl.DepthMask(GL_TRUE);
  m_gl.Enable(GL_DEPTH_TEST);
  m_gl.ActiveTexture(GL_TEXTURE0);
  check_gl_error(m_gl, "environment pass");
}

}  // namespace weft::render::detail
