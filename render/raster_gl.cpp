// The rasterizer's GL object owners (raster_gl.h).

#include "render/raster_gl.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>

namespace weft::render::detail {

namespace {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "positions are uploaded as-is");
static_assert(sizeof(Eigen::Vector2f) == 2 * sizeof(float), "UVs are uploaded as-is");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t),
              "triangles are uploaded as-is");

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

}  // namespace

void check_framebuffer(const GlFunctions& gl, GLenum target, const std::string& name) {
  const GLenum status = gl.CheckFramebufferStatus(target);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "%04X", status);
    throw std::runtime_error(name + " framebuffer is incomplete (status 0x" + hex + ")");
  }
}

GlProgram::GlProgram(const GlFunctions& gl, const char* vertex_source,
                     const char* fragment_source, const std::string& name)
    : m_gl(gl), m_id(link_program(gl, vertex_source, fragment_source, name)) {}

GlProgram::~GlProgram() {
  if (m_id != 0) m_gl.DeleteProgram(m_id);
}

void GlProgram::set(const char* name, const Eigen::Vector3f& v) const {
  m_gl.Uniform3f(m_gl.GetUniformLocation(m_id, name), v.x(), v.y(), v.z());
}

void GlProgram::set(const char* name, const Eigen::Vector3d& v) const {
  set(name, Eigen::Vector3f(v.cast<float>()));
}

void GlProgram::set(const char* name, const Eigen::Vector2f& v) const {
  m_gl.Uniform2f(m_gl.GetUniformLocation(m_id, name), v.x(), v.y());
}

void GlProgram::set(const char* name, const Eigen::Matrix4f& m) const {
  m_gl.UniformMatrix4fv(m_gl.GetUniformLocation(m_id, name), 1, GL_FALSE, m.data());
}

void GlProgram::set(const char* name, float x) const {
  m_gl.Uniform1f(m_gl.GetUniformLocation(m_id, name), x);
}

void GlProgram::set(const char* name, int x) const {
  m_gl.Uniform1i(m_gl.GetUniformLocation(m_id, name), x);
}

MeshBuffers::MeshBuffers(const GlFunctions& gl) : m_gl(gl) {
  m_gl.GenVertexArrays(1, &m_vao);
  m_gl.GenBuffers(1, &m_positions);
  m_gl.GenBuffers(1, &m_normals);
  m_gl.GenBuffers(1, &m_uvs);
  m_gl.GenBuffers(1, &m_colours);
  m_gl.GenBuffers(1, &m_indices);
  // Attribute 0: position, attribute 1: normal; 3 floats each, tightly packed.
  m_gl.BindVertexArray(m_vao);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_positions);
  m_gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(0);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_normals);
  m_gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(1);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_uvs);
  m_gl.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(2);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_colours);
  m_gl.VertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  m_gl.EnableVertexAttribArray(3);
  m_gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indices);  // recorded in the VAO
  m_gl.BindVertexArray(0);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, 0);
}

MeshBuffers::~MeshBuffers() {
  const GLuint buffers[] = {m_positions, m_normals, m_uvs, m_colours, m_indices};
  m_gl.DeleteBuffers(5, buffers);
  m_gl.DeleteVertexArrays(1, &m_vao);
}

void MeshBuffers::upload(const RenderMesh& mesh, const std::vector<Eigen::Vector3f>& colours) {
  const auto bytes = [](std::size_t count, std::size_t size) {
    return static_cast<GLsizeiptr>(count * size);
  };
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_positions);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(mesh.positions.size(), sizeof(Eigen::Vector3f)),
                  mesh.positions.data(), GL_STREAM_DRAW);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_normals);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(mesh.normals.size(), sizeof(Eigen::Vector3f)),
                  mesh.normals.data(), GL_STREAM_DRAW);
  const std::vector<Eigen::Vector2f> no_uvs(
      mesh.uvs.size() == mesh.positions.size() ? 0 : mesh.positions.size(),
      Eigen::Vector2f::Zero());
  const std::vector<Eigen::Vector2f>& uvs = no_uvs.empty() ? mesh.uvs : no_uvs;
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_uvs);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(uvs.size(), sizeof(Eigen::Vector2f)), uvs.data(),
                  GL_STREAM_DRAW);
  const std::vector<Eigen::Vector3f> no_colours(
      colours.size() == mesh.positions.size() ? 0 : mesh.positions.size(),
      Eigen::Vector3f::Zero());
  const std::vector<Eigen::Vector3f>& vertex_colours = no_colours.empty() ? colours : no_colours;
  m_gl.BindBuffer(GL_ARRAY_BUFFER, m_colours);
  m_gl.BufferData(GL_ARRAY_BUFFER, bytes(vertex_colours.size(), sizeof(Eigen::Vector3f)),
                  vertex_colours.data(), GL_STREAM_DRAW);
  m_gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  m_gl.BindVertexArray(m_vao);  // the element buffer binding belongs to the VAO
  m_gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                  bytes(mesh.triangles.size(), sizeof(std::array<std::uint32_t, 3>)),
                  mesh.triangles.data(), GL_STREAM_DRAW);
  m_gl.BindVertexArray(0);
  check_gl_error(m_gl, "uploading the mesh");
}

void MeshBuffers::draw(std::size_t first_index, GLsizei index_count) const {
  m_gl.BindVertexArray(m_vao);
  // The offset into the bound element buffer, in bytes, passed as a pointer (GL convention).
  const auto offset = static_cast<std::uintptr_t>(first_index * sizeof(std::uint32_t));
  m_gl.DrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT,
                    reinterpret_cast<const void*>(offset));
}

void RenderTargets::release() {
  // glDelete* ignore the name 0.
  const GLuint framebuffers[] = {m_msaa_fbo, m_resolve_fbo};
  const GLuint renderbuffers[] = {m_msaa_color, m_msaa_depth, m_resolve_color};
  m_gl.DeleteFramebuffers(2, framebuffers);
  m_gl.DeleteRenderbuffers(3, renderbuffers);
  m_msaa_fbo = m_resolve_fbo = m_msaa_color = m_msaa_depth = m_resolve_color = 0;
  m_samples = -1;  // stays invalid until ensure() succeeded
}

void RenderTargets::ensure(int width, int height, int samples) {
  if (width == m_width && height == m_height && samples == m_samples) return;
  release();
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
  check_gl_error(m_gl, "creating " + std::to_string(width) + "x" + std::to_string(height) +
                           " render targets");
  m_width = width;
  m_height = height;
  m_samples = samples;
}

void RenderTargets::bind_for_drawing() const {
  m_gl.BindFramebuffer(GL_FRAMEBUFFER, m_msaa_fbo);
  m_gl.Viewport(0, 0, m_width, m_height);
}

Image RenderTargets::read_back() {
  const int width = m_width, height = m_height;
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

}  // namespace weft::render::detail
