// The rasterizer's passes (raster_passes.h).

#include "render/raster_passes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "render/camera.h"
#include "render/raster_shaders.h"

namespace weft::render::detail {

namespace {

// Pixel rectangle [x0, x1) × [y0, y1), GL window coordinates (row 0 at the bottom).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};

// The pixels of a width × height viewport where the ground plane z = ground_z_m lies inside
// `footprint` (light clip x, y), widened by 2 pixels against rounding; the whole viewport when
// that cannot be bounded (a corner behind the camera, or a light nearly parallel to the ground).
PixelRect footprint_on_screen(const Eigen::AlignedBox2d& footprint,
                              const Eigen::Matrix4f& light_matrix,
                              const Eigen::Matrix4f& view_projection, double ground_z_m,
                              int width, int height) {
  const PixelRect whole{0, 0, width, height};
  if (footprint.isEmpty()) return {};
  const Eigen::Matrix4d light = light_matrix.cast<double>();
  const Eigen::Matrix4d camera = view_projection.cast<double>();
  // On the plane the light's clip x, y are affine in the world x, y (orthographic light).
  const Eigen::Matrix2d a = light.topLeftCorner<2, 2>();
  const Eigen::Vector2d b = light.block<2, 1>(0, 2) * ground_z_m + light.block<2, 1>(0, 3);
  if (!(std::abs(a.determinant()) > 1e-12)) return whole;
  const Eigen::Matrix2d a_inverse = a.inverse();
  Eigen::AlignedBox2d pixels;
  for (const auto corner : {Eigen::AlignedBox2d::BottomLeft, Eigen::AlignedBox2d::BottomRight,
                            Eigen::AlignedBox2d::TopLeft, Eigen::AlignedBox2d::TopRight}) {
    const Eigen::Vector2d xy = a_inverse * (footprint.corner(corner) - b);
    const Eigen::Vector4d clip = camera * Eigen::Vector4d(xy.x(), xy.y(), ground_z_m, 1.0);
    if (!(clip.w() > 1e-9)) return whole;
    pixels.extend(Eigen::Vector2d((0.5 * clip.x() / clip.w() + 0.5) * width,
                                  (0.5 * clip.y() / clip.w() + 0.5) * height));
  }
  const auto clamp_to = [](double v, int size) {
    return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(size)));
  };
  return {clamp_to(std::floor(pixels.min().x()) - 2.0, width),
          clamp_to(std::floor(pixels.min().y()) - 2.0, height),
          clamp_to(std::ceil(pixels.max().x()) + 2.0, width),
          clamp_to(std::ceil(pixels.max().y()) + 2.0, height)};
}

}  // namespace

Eigen::Matrix4f light_view_projection(const std::vector<const RenderMesh*>& meshes,
                                      const Eigen::Vector3d& light_unit) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = -lo;
  for (const RenderMesh* mesh : meshes) {
    for (const Eigen::Vector3f& p : mesh->positions) {
      lo = lo.cwiseMin(p.cast<double>());
      hi = hi.cwiseMax(p.cast<double>());
    }
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-3);  // metres

  Camera light;
  light.eye = centre + 2.0 * radius * light_unit;
  light.target = centre;
  light.up = std::abs(light_unit.z()) < 0.99 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  // Depth range [0.5 r, 4 r] from the eye: the mesh lies in [r, 3 r]; receivers beyond the far
  // plane are clamped in the shader and count as behind every caster.
  const double near_m = 0.5 * radius, far_m = 4.0 * radius;
  Eigen::Matrix4d ortho = Eigen::Matrix4d::Identity();
  ortho(0, 0) = 1.0 / radius;
  ortho(1, 1) = 1.0 / radius;
  ortho(2, 2) = -2.0 / (far_m - near_m);
  ortho(2, 3) = -(far_m + near_m) / (far_m - near_m);
  return ortho.cast<float>() * light.view_matrix();
}

Eigen::AlignedBox2d caster_footprint(const std::vector<const RenderMesh*>& casters,
                                     const Eigen::Matrix4f& light_matrix, double margin) {
  Eigen::AlignedBox2d box;  // empty
  const Eigen::Matrix4d light = light_matrix.cast<double>();
  for (const RenderMesh* mesh : casters) {
    for (const Eigen::Vector3f& p : mesh->positions) {
      box.extend((light * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0)).head<2>());
    }
  }
  if (box.isEmpty()) return box;
  box.min().array() -= margin;
  box.max().array() += margin;
  return box.intersection(Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
}

ShadowPass::ShadowPass(const GlFunctions& gl)
    : m_gl(gl), m_program(gl, shadow_vertex_shader, shadow_fragment_shader, "shadow") {}

ShadowPass::~ShadowPass() {
  m_gl.DeleteFramebuffers(1, &m_fbo);  // glDelete* ignore the name 0
  m_gl.DeleteTextures(1, &m_depth);
}

void ShadowPass::ensure_map() {
  if (m_fbo != 0) return;
  m_gl.GenTextures(1, &m_depth);
  m_gl.BindTexture(GL_TEXTURE_2D, m_depth);
  m_gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, shadow_map_size, shadow_map_size, 0,
                  GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
  // Linear filtering of depth comparisons gives 2x2 PCF per tap.
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  m_gl.BindTexture(GL_TEXTURE_2D, 0);
  m_gl.GenFramebuffers(1, &m_fbo);
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_fbo);
  m_gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m_depth, 0);
  m_gl.DrawBuffer(GL_NONE);
  m_gl.ReadBuffer(GL_NONE);
  check_framebuffer(m_gl, GL_FRAMEBUFFER, "shadow map");
  check_gl_error(m_gl, "creating the shadow map");
}

void ShadowPass::draw(const Eigen::Matrix4f& light_matrix,
                      const std::vector<std::pair<const MeshBuffers*, GLsizei>>& casters) {
  ensure_map();
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_fbo);
  m_gl.Viewport(0, 0, shadow_map_size, shadow_map_size);
  m_gl.DepthMask(GL_TRUE);
  m_gl.ClearDepth(1.0);
  m_gl.Clear(GL_DEPTH_BUFFER_BIT);
  m_gl.Enable(GL_DEPTH_TEST);
  m_gl.DepthFunc(GL_LESS);
  m_gl.Enable(GL_POLYGON_OFFSET_FILL);  // keeps the cloth's own depth off its shadow test
  m_gl.PolygonOffset(2.0f, 4.0f);
  m_program.use();
  m_program.set("u_light_view_projection", light_matrix);
  for (const auto& [buffers, count] : casters) {
    if (count > 0) buffers->draw(0, count);
  }
  m_gl.BindVertexArray(0);
  m_gl.Disable(GL_POLYGON_OFFSET_FILL);
  check_gl_error(m_gl, "shadow pass");
}

GroundPass::GroundPass(const GlFunctions& gl)
    : m_gl(gl),
      m_shadowed(gl, ground_vertex_shader, ground_fragment_shader, "ground"),
      m_unshadowed(gl, ground_vertex_shader, ground_fragment_source(false).c_str(),
                   "unshadowed ground") {
  m_gl.GenVertexArrays(1, &m_empty_vao);
}

GroundPass::~GroundPass() {
  m_gl.DeleteVertexArrays(1, &m_empty_vao);
}

void GroundPass::set_uniforms(const GlProgram& p, const RenderSettings& s,
                              const Eigen::Matrix4f& view_projection,
                              const Eigen::Matrix4f* shadow_matrix,
                              const EnvironmentShading& environment) const {
  p.use();
  p.set("u_view_projection", view_projection);
  // Centred under the camera target, so it stays put while a turntable orbits the eye.
  p.set("u_ground_center", Eigen::Vector3d(s.camera.target.x(), s.camera.target.y(), s.ground_z_m));
  p.set("u_half_size", static_cast<float>(s.ground_half_size_m));
  p.set("u_ground_color", s.ground_color);
  p.set("u_background", s.background);
  p.set("u_light_dir", Eigen::Vector3d(s.light_direction.normalized()));
  p.set("u_light_intensity", static_cast<float>(s.light_intensity));
  p.set("u_ambient", static_cast<float>(s.ambient));
  p.set("u_shading", s.shading == Shading::normals ? 1 : 0);
  p.set("u_use_environment", environment.on ? 1 : 0);
  p.set("u_environment_up", environment.up);
  p.set("u_environment_down", environment.down);
  p.set("u_blend_rim", environment.on && environment.background ? 1 : 0);
  // The shadow uniforms (absent from the unshadowed program: location −1, ignored).
  p.set("u_use_shadow", shadow_matrix ? 1 : 0);
  p.set("u_shadow_texel", 1.0f / static_cast<float>(shadow_map_size));
  p.set("u_shadow_map", 0);  // texture unit 0
  if (shadow_matrix) {
    // Shadow clip [−1, 1]³ → texture coordinates and depth [0, 1]³.
    Eigen::Matrix4f to_texture = Eigen::Matrix4f::Identity();
    to_texture.topLeftCorner<3, 3>() *= 0.5f;
    to_texture.topRightCorner<3, 1>().setConstant(0.5f);
    p.set("u_shadow_matrix", Eigen::Matrix4f(to_texture * *shadow_matrix));
  }
}

void GroundPass::draw(const RenderSettings& s, const Eigen::Matrix4f& view_projection,
                      const Eigen::Matrix4f* shadow_matrix, const Eigen::AlignedBox2d& footprint,
                      GLuint shadow_map, const EnvironmentShading& environment) {
  // Pushed back in depth so cloth lying on the ground wins.
  m_gl.Enable(GL_POLYGON_OFFSET_FILL);
  m_gl.PolygonOffset(1.0f, 4.0f);
  m_gl.BindVertexArray(m_empty_vao);
  // The shadow lookup runs only inside the screen rectangle of the casters' footprint; the
  // same square is drawn without it in the bands around (up to four), where it returns 1.
  const PixelRect in =
      shadow_matrix ? footprint_on_screen(footprint, *shadow_matrix, view_projection,
                                          s.ground_z_m, s.width, s.height)
                    : PixelRect{};
  const PixelRect bands[] = {{0, 0, s.width, in.y0},
                             {0, in.y1, s.width, s.height},
                             {0, in.y0, in.x0, in.y1},
                             {in.x1, in.y0, s.width, in.y1}};
  m_gl.Enable(GL_SCISSOR_TEST);
  if (environment.on && environment.background) {  // the rim fades into the map by alpha
    m_gl.Enable(GL_BLEND);
    m_gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  }
  const auto draw_in = [&](const PixelRect& r) {
    if (r.empty()) return;
    m_gl.Scissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
    m_gl.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  };
  if (!in.empty()) {
    set_uniforms(m_shadowed, s, view_projection, shadow_matrix, environment);
    m_gl.ActiveTexture(GL_TEXTURE0);
    m_gl.BindTexture(GL_TEXTURE_2D, shadow_map);
    draw_in(in);
    m_gl.BindTexture(GL_TEXTURE_2D, 0);
  }
  set_uniforms(m_unshadowed, s, view_projection, nullptr, environment);
  if (in.empty()) {
    draw_in({0, 0, s.width, s.height});
  } else {
    for (const PixelRect& band : bands) draw_in(band);
  }
  m_gl.Disable(GL_SCISSOR_TEST);
  m_gl.Disable(GL_BLEND);
  m_gl.BindVertexArray(0);
  m_gl.Disable(GL_POLYGON_OFFSET_FILL);
  check_gl_error(m_gl, "ground pass");
}

SurfacePass::SurfacePass(const GlFunctions& gl)
    : m_gl(gl), m_program(gl, cloth_vertex_shader, cloth_fragment_shader, "cloth") {}

SurfacePass::~SurfacePass() {
  m_gl.DeleteTextures(1, &m_texture.name);  // glDelete* ignore the name 0
  m_gl.DeleteTextures(1, &m_weave.name);
}

void SurfacePass::begin(const RenderSettings& s, const Eigen::Matrix4f& view_projection,
                        bool textured, const TexturePlacement& texture_placement,
                        const EnvironmentShading& environment) {
  m_program.use();
  m_program.set("u_view_projection", view_projection);
  m_program.set("u_eye", s.camera.eye);
  m_program.set("u_light_dir", Eigen::Vector3d(s.light_direction.normalized()));
  m_program.set("u_light_intensity", static_cast<float>(s.light_intensity));
  m_program.set("u_ambient", static_cast<float>(s.ambient));
  m_program.set("u_shading", s.shading == Shading::normals ? 1 : 0);
  m_program.set("u_use_environment", environment.on ? 1 : 0);
  m_program.set("u_sheen", s.shading == Shading::lit ? static_cast<float>(s.cloth_surface.sheen)
                                                       : 0.0f);
  m_program.set("u_sheen_roughness", static_cast<float>(s.cloth_surface.sheen_roughness));
  const Weave& weave = s.cloth_surface.weave;
  m_program.set("u_weave_depth", weave.normal_map ? static_cast<float>(weave.depth) : 0.0f);
  if (weave.normal_map) {
    bind_image(m_weave, weave.normal_map, GL_TEXTURE2, true);
    m_program.set("u_weave", 2);  // texture unit 2
    m_program.set("u_weave_repeat", Eigen::Vector2f(weave.repeat_m.cast<float>()));
  }
  if (environment.on) {
    for (int k = 0; k < 9; ++k) {
      const std::string name = "u_sh[" + std::to_string(k) + "]";
      m_program.set(name.c_str(), environment.polynomial[k]);
    }
  }
  if (textured) {
    bind_image(m_texture, s.cloth_surface.texture.image, GL_TEXTURE1, texture_placement.repeat);
    m_program.set("u_texture", 1);  // texture unit 1
    m_program.set("u_texture_origin", texture_placement.origin);
    m_program.set("u_texture_size", texture_placement.size);
    m_program.set("u_texture_back", texture_on_back(s) ? 1 : 0);
  }
}

void SurfacePass::bind_image(ImageTexture& texture, const std::shared_ptr<const Image>& owner,
                             GLenum unit, bool repeat) {
  texture.owner = owner;
  const Image& image = *owner;
  if (texture.name == 0) {
    m_gl.GenTextures(1, &texture.name);
    texture.image = nullptr;
  }
  m_gl.ActiveTexture(unit);
  m_gl.BindTexture(GL_TEXTURE_2D, texture.name);
  if (texture.image != &image) {
    // GL's t = 0 is the first row uploaded: the image's bottom row goes first (texture.h).
    const auto row_bytes = static_cast<std::size_t>(image.width()) * 3;
    std::vector<std::uint8_t> rows(row_bytes * static_cast<std::size_t>(image.height()));
    for (int y = 0; y < image.height(); ++y) {
      std::copy_n(image.data() + static_cast<std::size_t>(image.height() - 1 - y) * row_bytes,
                  row_bytes, rows.data() + static_cast<std::size_t>(y) * row_bytes);
    }
    m_gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    m_gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width(), image.height(), 0, GL_RGB,
                    GL_UNSIGNED_BYTE, rows.data());
    m_gl.GenerateMipmap(GL_TEXTURE_2D);
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    texture.image = &image;
  }
  const GLint wrap = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
  m_gl.ActiveTexture(GL_TEXTURE0);
  check_gl_error(m_gl, "uploading a cloth texture");
}

void SurfacePass::draw(const MeshBuffers& b, std::size_t first_index, GLsizei index_count,
                       const Eigen::Vector3f& front, const Eigen::Vector3f& back, bool cloth,
                       bool textured, bool vertex_coloured) {
  m_program.set("u_cloth", cloth ? 1 : 0);
  m_program.set("u_use_texture", textured ? 1 : 0);
  m_program.set("u_use_vertex_colour", vertex_coloured ? 1 : 0);
  m_program.set("u_front_color", front);
  m_program.set("u_back_color", back);
  b.draw(first_index, index_count);
  m_gl.BindVertexArray(0);
  check_gl_error(m_gl, "surface pass");
}

}  // namespace weft::render::detail
