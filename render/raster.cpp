// OpenGL 3.3 core rasterizer. Per render():
//   1. validate the settings and the meshes (computing vertex normals on a copy if missing);
//      the extra objects are merged into one mesh, drawn range by range in their colours,
//   2. upload positions, normals and triangles of the cloth and of the objects (the cloth
//      changes every frame),
//   3. shadow pass (ground on, lit): cloth and object depth from the key light, orthographic,
//   4. main pass into a multisampled FBO: clear to the background, ground, cloth, objects;
//      the ground runs its shadow lookup (5×5 PCF, most of a frame's cost under llvmpipe) only
//      inside the screen rectangle where the casters' shadow can fall, and a program without
//      it elsewhere (the same pixels: there the lookup returns 1),
//   5. resolve (glBlitFramebuffer) into a single-sample FBO, glFinish, glReadPixels,
//      and flip rows so that Image row 0 is the top.
// GL entry points come from the GlContext (gl_functions.h); nothing links GL directly.

#include "render/raster.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/gl_functions.h"
#include "render/raster_shaders.h"

namespace weft::render {

namespace {

using detail::check_gl_error;
using detail::GlFunctions;

constexpr int shadow_map_size = 2048;  // texels per side of the square shadow map

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "positions are uploaded as-is");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t),
              "triangles are uploaded as-is");

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// Bad input in the mesh (validate, render_mesh.h), and at most INT_MAX/3 triangles (one draw
// call). Messages start with `name` ("RenderMesh", "object 2").
void validate_for_gl(const RenderMesh& mesh, const std::string& name = "RenderMesh") {
  validate(mesh, name);
  if (mesh.triangles.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max() / 3)) {
    throw std::invalid_argument(name + ": too many triangles for one draw call");
  }
}

GLuint compile_shader(const GlFunctions& gl, GLenum type, const char* source,
                      const std::string& name) {
  const GLuint shader = gl.CreateShader(type);
  if (shader == 0) throw std::runtime_error(name + ": glCreateShader failed");
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl.DeleteShader(shader);
    throw std::runtime_error(name + " failed to compile:\n" + log.c_str());
  }
  return shader;
}

// Compiles and links a vertex + fragment program; throws with the compiler/linker log.
GLuint link_program(const GlFunctions& gl, const char* vertex_source, const char* fragment_source,
                    const std::string& name) {
  const GLuint vertex =
      compile_shader(gl, GL_VERTEX_SHADER, vertex_source, name + " vertex shader");
  GLuint fragment = 0;
  try {
    fragment = compile_shader(gl, GL_FRAGMENT_SHADER, fragment_source, name + " fragment shader");
  } catch (...) {
    gl.DeleteShader(vertex);
    throw;
  }
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vertex);
  gl.AttachShader(program, fragment);
  gl.LinkProgram(program);
  gl.DeleteShader(vertex);  // flagged; freed with the program
  gl.DeleteShader(fragment);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl.DeleteProgram(program);
    throw std::runtime_error(name + " program failed to link:\n" + log.c_str());
  }
  check_gl_error(gl, name + " program");
  return program;
}

void check_framebuffer(const GlFunctions& gl, GLenum target, const std::string& name) {
  const GLenum status = gl.CheckFramebufferStatus(target);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(name + " framebuffer is incomplete (status 0x" + [status] {
      char hex[16];
      std::snprintf(hex, sizeof hex, "%04X", status);
      return std::string(hex);
    }() + ")");
  }
}

// Index range of one object in the merged object mesh, and its colour.
struct ObjectRange {
  std::size_t first_index = 0;  // into the element buffer (3 per triangle)
  GLsizei index_count = 0;
  Eigen::Vector3f color;
};

// All objects as one mesh (with normals), and where each one's triangles lie in it.
RenderMesh merge_objects(const std::vector<RenderObject>& objects,
                         std::vector<ObjectRange>& ranges) {
  RenderMesh merged;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const std::string name = "object " + std::to_string(k);
    const RenderObject& object = objects[k];
    validate_for_gl(object.mesh, name);
    if (!object.color.allFinite()) throw std::invalid_argument(name + ": colour is not finite");
    if (merged.positions.size() + object.mesh.positions.size() >
        std::numeric_limits<std::uint32_t>::max()) {
      throw std::invalid_argument(name + ": too many vertices in all objects together");
    }
    RenderMesh storage;
    const RenderMesh& mesh = with_normals(object.mesh, storage);
    const auto base = static_cast<std::uint32_t>(merged.positions.size());
    ranges.push_back({3 * merged.triangles.size(), static_cast<GLsizei>(3 * mesh.triangles.size()),
                      object.color});
    merged.positions.insert(merged.positions.end(), mesh.positions.begin(), mesh.positions.end());
    merged.normals.insert(merged.normals.end(), mesh.normals.begin(), mesh.normals.end());
    for (const auto& t : mesh.triangles)
      merged.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  validate_for_gl(merged, "objects");  // the total must fit one draw call too
  return merged;
}

// World → light clip space for the shadow pass: an orthographic box looking along
// −light_direction that encloses the sphere around the meshes' bounding box.
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

// Pixel rectangle [x0, x1) × [y0, y1), GL window coordinates (row 0 at the bottom).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};

// Where the casters' shadow can fall, in the light's clip x, y: their bounding box widened by
// `margin` (clip units), within [−1, 1]² (the shadow map).
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

struct RasterRenderer::Impl {
  explicit Impl(std::unique_ptr<GlContext> context);
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects);
  std::string description() const { return m_context->description(); }

 private:
  // Vertex array and buffers of one mesh: attribute 0 position, 1 normal, 3 floats each;
  // 2 UV (material coordinates), 2 floats, zero for meshes without UVs.
  struct MeshBuffers {
    GLuint vao = 0, positions = 0, normals = 0, uvs = 0, indices = 0;
  };

  void create_buffers(MeshBuffers& b);
  void release_buffers(MeshBuffers& b);
  void release_gl();
  void ensure_targets(int width, int height, int samples);
  void ensure_shadow_map();
  // Binds the cloth texture to texture unit 1, uploading it when the image changed.
  void bind_cloth_texture(const Image& image);
  void upload(const MeshBuffers& b, const RenderMesh& mesh);
  void draw_shadow_map(const Eigen::Matrix4f& light_matrix, GLsizei cloth_index_count,
                       GLsizei object_index_count);
  // shadow_matrix: the light's view-projection when there is a shadow, and the casters' shadow
  // footprint in its clip x, y (caster_footprint).
  void draw_ground(const RenderSettings& s, const Eigen::Matrix4f& view_projection,
                   const Eigen::Matrix4f* shadow_matrix, const Eigen::AlignedBox2d& footprint);
  void set_ground_uniforms(GLuint p, const RenderSettings& s,
                           const Eigen::Matrix4f& view_projection,
                           const Eigen::Matrix4f* shadow_matrix);
  // Lit (or normals-shaded) surfaces: the cloth program with its uniforms set, then one draw
  // per index range with its front and back colours.
  void use_surface_program(const RenderSettings& s, const Eigen::Matrix4f& view_projection);
  void draw_surface(const MeshBuffers& b, std::size_t first_index, GLsizei index_count,
                    const Eigen::Vector3f& front, const Eigen::Vector3f& back,
                    bool textured = false);
  Image read_back(int width, int height);

  GLint uniform(GLuint program, const char* name) const {
    return m_gl.GetUniformLocation(program, name);
  }
  void set(GLuint program, const char* name, const Eigen::Vector3f& v) const {
    m_gl.Uniform3f(uniform(program, name), v.x(), v.y(), v.z());
  }
  void set(GLuint program, const char* name, const Eigen::Vector3d& v) const {
    set(program, name, Eigen::Vector3f(v.cast<float>()));
  }
  void set(GLuint program, const char* name, const Eigen::Matrix4f& m) const {
    m_gl.UniformMatrix4fv(uniform(program, name), 1, GL_FALSE, m.data());  // column-major
  }
  void set(GLuint program, const char* name, const Eigen::Vector2f& v) const {
    m_gl.Uniform2f(uniform(program, name), v.x(), v.y());
  }
  void set(GLuint program, const char* name, float x) const {
    m_gl.Uniform1f(uniform(program, name), x);
  }
  void set(GLuint program, const char* name, int x) const {
    m_gl.Uniform1i(uniform(program, name), x);
  }

  std::unique_ptr<GlContext> m_context;  // declared first: destroyed after the GL objects
  GlFunctions m_gl;
  GLint m_max_samples = 0, m_max_size = 0;
  GLuint m_cloth_program = 0, m_ground_program = 0, m_shadow_program = 0;
  GLuint m_unshadowed_ground_program = 0;  // the ground without the shadow lookup
  MeshBuffers m_cloth, m_objects;
  GLuint m_empty_vao = 0;                       // the ground needs no attributes
  GLuint m_shadow_fbo = 0, m_shadow_depth = 0;  // created on first use
  GLuint m_cloth_texture = 0;                   // created on first use
  const Image* m_cloth_texture_image = nullptr;  // what it holds (compared by address)
  std::shared_ptr<const Image> m_cloth_texture_owner;  // keeps that address valid
  // Size-dependent render targets, recreated when width, height or samples change.
  int m_target_width = 0, m_target_height = 0, m_target_samples = -1;
  GLuint m_msaa_fbo = 0, m_msaa_color = 0, m_msaa_depth = 0;
  GLuint m_resolve_fbo = 0, m_resolve_color = 0;
  std::vector<std::uint8_t> m_read_buffer;  // RGBA rows as glReadPixels returns them
};

RasterRenderer::Impl::Impl(std::unique_ptr<GlContext> context) : m_context(std::move(context)) {
  if (!m_context) throw std::invalid_argument("RasterRenderer: no GL context given");
  m_context->make_current();
  m_gl = detail::load_gl_functions(*m_context);
  try {
    m_gl.GetIntegerv(GL_MAX_SAMPLES, &m_max_samples);
    m_gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &m_max_size);
    m_cloth_program =
        link_program(m_gl, detail::cloth_vertex_shader, detail::cloth_fragment_shader, "cloth");
    m_ground_program =
        link_program(m_gl, detail::ground_vertex_shader, detail::ground_fragment_shader, "ground");
    m_unshadowed_ground_program =
        link_program(m_gl, detail::ground_vertex_shader,
                     detail::ground_fragment_source(false).c_str(), "unshadowed ground");
    m_shadow_program =
        link_program(m_gl, detail::shadow_vertex_shader, detail::shadow_fragment_shader, "shadow");

    m_gl.GenVertexArrays(1, &m_empty_vao);
    create_buffers(m_cloth);
    create_buffers(m_objects);
    check_gl_error(m_gl, "RasterRenderer setup");
  } catch (...) {
    release_gl();
    throw;
  }
}

RasterRenderer::Impl::~Impl() {
  try {
    m_context->make_current();
    release_gl();
  } catch (...) {
    // The context is going away with everything it holds; nothing more to do.
  }
}

void RasterRenderer::Impl::create_buffers(MeshBuffers& b) {
  m_gl.GenVertexArrays(1, &b.vao);
  m_gl.GenBuffers(1, &b.positions);
  m_gl.GenBuffers(1, &b.normals);
  m_gl.GenBuffers(1, &b.uvs);
  m_gl.GenBuffers(1, &b.indices);
  // Attribute 0: position, attribute 1: normal; 3 floats each, tightly packed.
  m_gl.BindVertexArray(b.vao);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, b.positions);
  m_gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(0);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, b.normals);
  m_gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(1);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, b.uvs);
  m_gl.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(2);
  m_gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.indices);  // recorded in the VAO
  m_gl.BindVertexArray(0);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, 0);
}

void RasterRenderer::Impl::release_buffers(MeshBuffers& b) {
  const GLuint buffers[] = {b.positions, b.normals, b.uvs, b.indices};
  if (m_gl.DeleteBuffers) m_gl.DeleteBuffers(4, buffers);
  if (m_gl.DeleteVertexArrays) m_gl.DeleteVertexArrays(1, &b.vao);
  b = MeshBuffers{};
}

void RasterRenderer::Impl::release_gl() {
  // glDelete* ignore the name 0, so this is safe on a partially built renderer.
  const GLuint framebuffers[] = {m_msaa_fbo, m_resolve_fbo, m_shadow_fbo};
  const GLuint renderbuffers[] = {m_msaa_color, m_msaa_depth, m_resolve_color};
  if (m_gl.DeleteFramebuffers) m_gl.DeleteFramebuffers(3, framebuffers);
  if (m_gl.DeleteRenderbuffers) m_gl.DeleteRenderbuffers(3, renderbuffers);
  if (m_gl.DeleteTextures) m_gl.DeleteTextures(1, &m_shadow_depth);
  if (m_gl.DeleteTextures) m_gl.DeleteTextures(1, &m_cloth_texture);
  m_cloth_texture = 0;
  m_cloth_texture_image = nullptr;
  m_cloth_texture_owner.reset();
  release_buffers(m_cloth);
  release_buffers(m_objects);
  if (m_gl.DeleteVertexArrays) m_gl.DeleteVertexArrays(1, &m_empty_vao);
  for (GLuint program :
       {m_cloth_program, m_ground_program, m_unshadowed_ground_program, m_shadow_program}) {
    if (m_gl.DeleteProgram && program != 0) m_gl.DeleteProgram(program);
  }
  m_msaa_fbo = m_resolve_fbo = m_shadow_fbo = 0;
  m_msaa_color = m_msaa_depth = m_resolve_color = m_shadow_depth = 0;
  m_empty_vao = 0;
  m_cloth_program = m_ground_program = m_unshadowed_ground_program = m_shadow_program = 0;
  m_target_width = m_target_height = 0;
  m_target_samples = -1;
}

void RasterRenderer::Impl::ensure_targets(int width, int height, int samples) {
  if (width == m_target_width && height == m_target_height && samples == m_target_samples) return;
  const GLuint framebuffers[] = {m_msaa_fbo, m_resolve_fbo};
  const GLuint renderbuffers[] = {m_msaa_color, m_msaa_depth, m_resolve_color};
  m_gl.DeleteFramebuffers(2, framebuffers);
  m_gl.DeleteRenderbuffers(3, renderbuffers);
  m_msaa_fbo = m_resolve_fbo = m_msaa_color = m_msaa_depth = m_resolve_color = 0;
  m_target_samples = -1;  // stays invalid until everything below succeeded

  // Multisampled colour (RGBA8) + depth (24 bit) to draw into; samples 0 = no multisampling.
  m_gl.GenRenderbuffers(1, &m_msaa_color);
  m_gl.BindRenderbuffer(GL_RENDERBUFFER, m_msaa_color);
  m_gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
  m_gl.GenRenderbuffers(1, &m_msaa_depth);
  m_gl.BindRenderbuffer(GL_RENDERBUFFER, m_msaa_depth);
  m_gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width,
                                      height);
  m_gl.GenFramebuffers(1, &m_msaa_fbo);
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_msaa_fbo);
  m_gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m_msaa_color);
  m_gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m_msaa_depth);
  check_framebuffer(m_gl, GL_FRAMEBUFFER, "multisampled (" + std::to_string(samples) + " samples)");

  // Single-sample colour the multisampled one is resolved into and read from.
  m_gl.GenRenderbuffers(1, &m_resolve_color);
  m_gl.BindRenderbuffer(GL_RENDERBUFFER, m_resolve_color);
  m_gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, 0, GL_RGBA8, width, height);
  m_gl.GenFramebuffers(1, &m_resolve_fbo);
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_resolve_fbo);
  m_gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                               m_resolve_color);
  check_framebuffer(m_gl, GL_FRAMEBUFFER, "resolve");
  m_gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
  check_gl_error(m_gl, "creating " + size_text(width, height) + " render targets");

  m_target_width = width;
  m_target_height = height;
  m_target_samples = samples;
}

void RasterRenderer::Impl::ensure_shadow_map() {
  if (m_shadow_fbo != 0) return;
  m_gl.GenTextures(1, &m_shadow_depth);
  m_gl.BindTexture(GL_TEXTURE_2D, m_shadow_depth);
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
  m_gl.GenFramebuffers(1, &m_shadow_fbo);
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_shadow_fbo);
  m_gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m_shadow_depth, 0);
  m_gl.DrawBuffer(GL_NONE);
  m_gl.ReadBuffer(GL_NONE);
  check_framebuffer(m_gl, GL_FRAMEBUFFER, "shadow map");
  check_gl_error(m_gl, "creating the shadow map");
}

void RasterRenderer::Impl::upload(const MeshBuffers& b, const RenderMesh& mesh) {
  const auto bytes = [](std::size_t count, std::size_t size) {
    return static_cast<GLsizeiptr>(count * size);
  };
  m_gl.BindBuffer(GL_ARRAY_BUFFER, b.positions);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(mesh.positions.size(), sizeof(Eigen::Vector3f)),
                  mesh.positions.data(), GL_STREAM_DRAW);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, b.normals);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(mesh.normals.size(), sizeof(Eigen::Vector3f)),
                  mesh.normals.data(), GL_STREAM_DRAW);
  static_assert(sizeof(Eigen::Vector2f) == 2 * sizeof(float), "UVs are uploaded as-is");
  const std::vector<Eigen::Vector2f> no_uvs(
      mesh.uvs.size() == mesh.positions.size() ? 0 : mesh.positions.size(),
      Eigen::Vector2f::Zero());
  const std::vector<Eigen::Vector2f>& uvs = no_uvs.empty() ? mesh.uvs : no_uvs;
  m_gl.BindBuffer(GL_ARRAY_BUFFER, b.uvs);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(uvs.size(), sizeof(Eigen::Vector2f)), uvs.data(),
                  GL_STREAM_DRAW);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  m_gl.BindVertexArray(b.vao);  // the element buffer binding belongs to the VAO
  m_gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                  bytes(mesh.triangles.size(), sizeof(std::array<std::uint32_t, 3>)),
                  mesh.triangles.data(), GL_STREAM_DRAW);
  m_gl.BindVertexArray(0);
  check_gl_error(m_gl, "uploading the mesh");
}

void RasterRenderer::Impl::draw_shadow_map(const Eigen::Matrix4f& light_matrix,
                                           GLsizei cloth_index_count, GLsizei object_index_count) {
  ensure_shadow_map();
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_shadow_fbo);
  m_gl.Viewport(0, 0, shadow_map_size, shadow_map_size);
  m_gl.DepthMask(GL_TRUE);
  m_gl.ClearDepth(1.0);
  m_gl.Clear(GL_DEPTH_BUFFER_BIT);
  m_gl.Enable(GL_DEPTH_TEST);
  m_gl.DepthFunc(GL_LESS);
  m_gl.Enable(GL_POLYGON_OFFSET_FILL);  // keeps the cloth's own depth off its shadow test
  m_gl.PolygonOffset(2.0f, 4.0f);
  m_gl.UseProgram(m_shadow_program);
  set(m_shadow_program, "u_light_view_projection", light_matrix);
  for (const auto& [buffers, count] :
       {std::pair{&m_cloth, cloth_index_count}, std::pair{&m_objects, object_index_count}}) {
    if (count == 0) continue;
    m_gl.BindVertexArray(buffers->vao);
    m_gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
  }
  m_gl.BindVertexArray(0);
  m_gl.Disable(GL_POLYGON_OFFSET_FILL);
  check_gl_error(m_gl, "shadow pass");
}

void RasterRenderer::Impl::set_ground_uniforms(GLuint p, const RenderSettings& s,
                                               const Eigen::Matrix4f& view_projection,
                                               const Eigen::Matrix4f* shadow_matrix) {
  m_gl.UseProgram(p);
  set(p, "u_view_projection", view_projection);
  // Centred under the camera target, so it stays put while a turntable orbits the eye.
  set(p, "u_ground_center",
      Eigen::Vector3d(s.camera.target.x(), s.camera.target.y(), s.ground_z_m));
  set(p, "u_half_size", static_cast<float>(s.ground_half_size_m));
  set(p, "u_ground_color", s.ground_color);
  set(p, "u_background", s.background);
  set(p, "u_light_dir", Eigen::Vector3d(s.light_direction.normalized()));
  set(p, "u_light_intensity", static_cast<float>(s.light_intensity));
  set(p, "u_ambient", static_cast<float>(s.ambient));
  set(p, "u_shading", s.shading == Shading::normals ? 1 : 0);
  // The shadow uniforms (absent from the unshadowed program: location −1, ignored).
  set(p, "u_use_shadow", shadow_matrix ? 1 : 0);
  set(p, "u_shadow_texel", 1.0f / static_cast<float>(shadow_map_size));
  set(p, "u_shadow_map", 0);  // texture unit 0
  if (shadow_matrix) {
    // Shadow clip [−1, 1]³ → texture coordinates and depth [0, 1]³.
    Eigen::Matrix4f to_texture = Eigen::Matrix4f::Identity();
    to_texture.topLeftCorner<3, 3>() *= 0.5f;
    to_texture.topRightCorner<3, 1>().setConstant(0.5f);
    set(p, "u_shadow_matrix", Eigen::Matrix4f(to_texture * *shadow_matrix));
  }
}

void RasterRenderer::Impl::draw_ground(const RenderSettings& s,
                                       const Eigen::Matrix4f& view_projection,
                                       const Eigen::Matrix4f* shadow_matrix,
                                       const Eigen::AlignedBox2d& footprint) {
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
  const auto draw_in = [&](const PixelRect& r) {
    if (r.empty()) return;
    m_gl.Scissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
    m_gl.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  };
  if (!in.empty()) {
    set_ground_uniforms(m_ground_program, s, view_projection, shadow_matrix);
    m_gl.ActiveTexture(GL_TEXTURE0);
    m_gl.BindTexture(GL_TEXTURE_2D, m_shadow_depth);
    draw_in(in);
    m_gl.BindTexture(GL_TEXTURE_2D, 0);
  }
  set_ground_uniforms(m_unshadowed_ground_program, s, view_projection, nullptr);
  if (in.empty()) {
    draw_in({0, 0, s.width, s.height});
  } else {
    for (const PixelRect& band : bands) draw_in(band);
  }
  m_gl.Disable(GL_SCISSOR_TEST);
  m_gl.BindVertexArray(0);
  m_gl.Disable(GL_POLYGON_OFFSET_FILL);
  check_gl_error(m_gl, "ground pass");
}

void RasterRenderer::Impl::use_surface_program(const RenderSettings& s,
                                               const Eigen::Matrix4f& view_projection) {
  const GLuint p = m_cloth_program;
  m_gl.UseProgram(p);
  set(p, "u_view_projection", view_projection);
  set(p, "u_eye", s.camera.eye);
  set(p, "u_light_dir", Eigen::Vector3d(s.light_direction.normalized()));
  set(p, "u_light_intensity", static_cast<float>(s.light_intensity));
  set(p, "u_ambient", static_cast<float>(s.ambient));
  set(p, "u_shading", s.shading == Shading::normals ? 1 : 0);
}

void RasterRenderer::Impl::bind_cloth_texture(const Image& image) {
  if (m_cloth_texture == 0) {
    m_gl.GenTextures(1, &m_cloth_texture);
    m_cloth_texture_image = nullptr;
  }
  m_gl.ActiveTexture(GL_TEXTURE1);
  m_gl.BindTexture(GL_TEXTURE_2D, m_cloth_texture);
  if (m_cloth_texture_image != &image) {
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
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    m_gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    m_cloth_texture_image = &image;
  }
  m_gl.ActiveTexture(GL_TEXTURE0);
  check_gl_error(m_gl, "uploading the cloth texture");
}

void RasterRenderer::Impl::draw_surface(const MeshBuffers& b, std::size_t first_index,
                                        GLsizei index_count, const Eigen::Vector3f& front,
                                        const Eigen::Vector3f& back, bool textured) {
  set(m_cloth_program, "u_use_texture", textured ? 1 : 0);
  set(m_cloth_program, "u_front_color", front);
  set(m_cloth_program, "u_back_color", back);
  m_gl.BindVertexArray(b.vao);
  // The offset into the bound element buffer, in bytes, passed as a pointer (GL convention).
  const auto offset = static_cast<std::uintptr_t>(first_index * sizeof(std::uint32_t));
  m_gl.DrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT,
                    reinterpret_cast<const void*>(offset));
  m_gl.BindVertexArray(0);
  check_gl_error(m_gl, "surface pass");
}

Image RasterRenderer::Impl::read_back(int width, int height) {
  m_gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m_msaa_fbo);
  m_gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, m_resolve_fbo);
  m_gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  m_gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m_resolve_fbo);
  m_gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  m_gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  m_gl.Finish();
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 4;
  std::vector<std::uint8_t>& rgba = m_read_buffer;  // kept: no fresh pages every frame
  rgba.resize(row_bytes * static_cast<std::size_t>(height));
  m_gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl_error(m_gl, "reading back the image");

  // GL rows run bottom to top; Image rows top to bottom.
  Image image(width, height);
  std::uint8_t* out = image.data();
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = rgba.data() + static_cast<std::size_t>(height - 1 - y) * row_bytes;
    for (int x = 0; x < width; ++x, in += 4, out += 3) {
      out[0] = in[0];
      out[1] = in[1];
      out[2] = in[2];
    }
  }
  return image;
}

Image RasterRenderer::Impl::render(const RenderMesh& cloth_input, const RenderSettings& s,
                                   const std::vector<RenderObject>& objects) {
  m_context->make_current();
  validate(s, m_max_size);
  validate(s.cloth_surface);
  validate_for_gl(cloth_input);
  // Vertex normals are required; computed on a copy when missing or stale in size.
  RenderMesh cloth_storage;
  const RenderMesh& cloth = with_normals(cloth_input, cloth_storage);
  std::vector<ObjectRange> ranges;
  const RenderMesh merged = merge_objects(objects, ranges);
  const auto cloth_count = static_cast<GLsizei>(3 * cloth.triangles.size());
  const auto object_count = static_cast<GLsizei>(3 * merged.triangles.size());

  const int samples = s.msaa_samples <= 1 ? 0 : std::min(s.msaa_samples, int{m_max_samples});
  ensure_targets(s.width, s.height, samples);
  if (cloth_count > 0) upload(m_cloth, cloth);
  if (object_count > 0) upload(m_objects, merged);

  const Eigen::Vector3d light_unit = s.light_direction.normalized();
  const bool shadow = s.ground && s.shading == Shading::lit && cloth_count + object_count > 0 &&
                      light_unit.z() > 1e-6 && s.light_intensity > 0.0;
  Eigen::Matrix4f light_matrix = Eigen::Matrix4f::Identity();
  Eigen::AlignedBox2d footprint;  // of the casters' shadow, light clip x, y
  if (shadow) {
    light_matrix = light_view_projection({&cloth, &merged}, light_unit);
    draw_shadow_map(light_matrix, cloth_count, object_count);
    // Beyond the PCF's reach (±3 texels, bilinear: under 5) of every caster texel.
    footprint = caster_footprint({&cloth, &merged}, light_matrix, 8.0 * 2.0 / shadow_map_size);
  }

  const double aspect = static_cast<double>(s.width) / static_cast<double>(s.height);
  const Eigen::Matrix4f view_projection =
      s.camera.projection_matrix(aspect) * s.camera.view_matrix();

  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_msaa_fbo);
  m_gl.Viewport(0, 0, s.width, s.height);
  m_gl.Enable(GL_MULTISAMPLE);
  m_gl.DepthMask(GL_TRUE);
  m_gl.ClearColor(s.background.x(), s.background.y(), s.background.z(), 1.0f);
  m_gl.ClearDepth(1.0);
  m_gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m_gl.Enable(GL_DEPTH_TEST);
  m_gl.DepthFunc(GL_LESS);
  m_gl.Disable(GL_CULL_FACE);  // two-sided cloth
  check_gl_error(m_gl, "starting the main pass");
  if (s.ground) draw_ground(s, view_projection, shadow ? &light_matrix : nullptr, footprint);
  if (cloth_count + object_count > 0) {
    use_surface_program(s, view_projection);
    const ClothTexture& texture = s.cloth_surface.texture;
    const bool textured = texture.image && cloth.uvs.size() == cloth.positions.size();
    if (textured) {
      m_cloth_texture_owner = texture.image;
      bind_cloth_texture(*texture.image);
      set(m_cloth_program, "u_texture", 1);  // texture unit 1
      set(m_cloth_program, "u_texture_repeat",
          Eigen::Vector2f(texture.repeat_m.cast<float>()));
    }
    if (cloth_count > 0)
      draw_surface(m_cloth, 0, cloth_count, s.front_color, s.back_color, textured);
    for (const ObjectRange& r : ranges) {
      if (r.index_count > 0)
        draw_surface(m_objects, r.first_index, r.index_count, r.color, r.color);
    }
  }
  return read_back(s.width, s.height);
}

RasterRenderer::RasterRenderer(std::unique_ptr<GlContext> context)
    : m_impl(std::make_unique<Impl>(std::move(context))) {}

RasterRenderer::~RasterRenderer() = default;

Image RasterRenderer::render(const RenderMesh& mesh, const RenderSettings& settings) {
  return m_impl->render(mesh, settings, {});
}

Image RasterRenderer::render(const RenderMesh& cloth, const RenderSettings& settings,
                             const std::vector<RenderObject>& objects) {
  return m_impl->render(cloth, settings, objects);
}

std::string RasterRenderer::description() const {
  return m_impl->description();
}

}  // namespace weft::render
