#pragma once
// Private to render/: the rasterizer's GL objects as small owners (raster.cpp composes them):
// a linked program with its uniform setters, one mesh's vertex array and buffers, and the
// size-dependent render targets the main pass draws into and the image is read back from.
// Each deletes its GL names in its destructor; the owner of the GlContext keeps it current
// while they are created and destroyed.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "render/gl_functions.h"
#include "render/image.h"
#include "render/render_mesh.h"

namespace weft::render::detail {

// Throws std::runtime_error("<name> framebuffer is incomplete (status 0x…)") unless the
// framebuffer bound to `target` is complete.
void check_framebuffer(const GlFunctions& gl, GLenum target, const std::string& name);

// A vertex + fragment program, compiled and linked (throws std::runtime_error with the
// compiler or linker log), and its uniforms set by name (an absent uniform is ignored).
class GlProgram {
 public:
  GlProgram(const GlFunctions& gl, const char* vertex_source, const char* fragment_source,
            const std::string& name);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  void use() const { m_gl.UseProgram(m_id); }
  // The program must be in use.
  void set(const char* name, const Eigen::Vector3f& v) const;
  void set(const char* name, const Eigen::Vector3d& v) const;  // as floats
  void set(const char* name, const Eigen::Vector2f& v) const;
  void set(const char* name, const Eigen::Matrix4f& m) const;  // column-major, as Eigen's
  void set(const char* name, float x) const;
  void set(const char* name, int x) const;

 private:
  const GlFunctions& m_gl;
  GLuint m_id = 0;
};

// One mesh on the GPU: a vertex array with attribute 0 position, 1 normal (3 floats each) and
// 2 UV (material coordinates, 2 floats; zero for meshes without UVs), 3 colour (3 floats; the
// strain false colour, zero when not given), and its element buffer.
class MeshBuffers {
 public:
  explicit MeshBuffers(const GlFunctions& gl);
  ~MeshBuffers();
  MeshBuffers(const MeshBuffers&) = delete;
  MeshBuffers& operator=(const MeshBuffers&) = delete;

  // Replaces the buffers' contents by the mesh's (normals required, one per position) and
  // `colours` (one per position, or none).
  void upload(const RenderMesh& mesh, const std::vector<Eigen::Vector3f>& colours = {});
  // Draws index_count indices from first_index (3 per triangle) with the program in use.
  void draw(std::size_t first_index, GLsizei index_count) const;

 private:
  const GlFunctions& m_gl;
  GLuint m_vao = 0, m_positions = 0, m_normals = 0, m_uvs = 0, m_colours = 0, m_indices = 0;
};

// The multisampled colour + depth framebuffer the main pass draws into and the single-sample
// one it is resolved into, recreated when width, height or samples change.
class RenderTargets {
 public:
  explicit RenderTargets(const GlFunctions& gl) : m_gl(gl) {}
  ~RenderTargets() { release(); }
  RenderTargets(const RenderTargets&) = delete;
  RenderTargets& operator=(const RenderTargets&) = delete;

  // samples 0: no multisampling. Throws std::runtime_error when a framebuffer is incomplete.
  void ensure(int width, int height, int samples);
  // Binds the multisampled framebuffer for drawing, the viewport its size.
  void bind_for_drawing() const;
  // Resolves (glBlitFramebuffer), waits (glFinish), reads back and flips rows so that Image
  // row 0 is the top.
  Image read_back();

 private:
  void release();

  const GlFunctions& m_gl;
  int m_width = 0, m_height = 0, m_samples = -1;
  GLuint m_msaa_fbo = 0, m_msaa_color = 0, m_msaa_depth = 0;
  GLuint m_resolve_fbo = 0, m_resolve_color = 0;
  std::vector<std::uint8_t> m_read_buffer;  // RGBA rows as glReadPixels returns them
};

}  // namespace weft::render::detail
