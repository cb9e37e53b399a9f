#pragma once
// Private to render/: the rasterizer's passes (raster.cpp runs them in this order):
//   shadow  — depth of the casters (cloth, objects) from the key light into a shadow map,
//   ground  — the ground square, its shadow lookup (5×5 PCF, most of a frame's cost under
//             llvmpipe) only inside the screen rectangle where the casters' shadow can fall,
//             a program without it elsewhere (the same pixels: there the lookup returns 1),
//   surface — cloth and objects, lit (or normals-shaded), two-sided, the cloth textured.
// Under an environment map (render/environment.h) the map is drawn first, behind everything,
// when it is the background, and its spherical-harmonic irradiance replaces the ambient light.
// And the light's geometry the first two share.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <utility>
#include <vector>

#include "render/gl_functions.h"
#include "render/image.h"
#include "render/environment.h"
#include "render/raster_gl.h"
#include "render/render_mesh.h"
#include "render/render_settings.h"

namespace weft::render::detail {

constexpr int shadow_map_size = 2048;  // texels per side of the square shadow map

// World → light clip space for the shadow pass: an orthographic box looking along
// −light_unit that encloses the sphere around the meshes' bounding box.
Eigen::Matrix4f light_view_projection(const std::vector<const RenderMesh*>& meshes,
                                      const Eigen::Vector3d& light_unit);

// Where the casters' shadow can fall, in the light's clip x, y: their bounding box widened by
// `margin` (clip units), within [−1, 1]² (the shadow map).
Eigen::AlignedBox2d caster_footprint(const std::vector<const RenderMesh*>& casters,
                                     const Eigen::Matrix4f& light_matrix, double margin);

// What the ground and surface passes need of an environment map (render/environment.h): its
// reflected radiance as a polynomial in the normal (9 spherical-harmonic terms), and its value
// for the ground's two sides.
struct EnvironmentShading {
  bool on = false;
  bool background = false;  // the map is drawn behind everything; the ground fades into it
  ShCoefficients polynomial{};
  Eigen::Vector3f up = Eigen::Vector3f::Zero(), down = Eigen::Vector3f::Zero();
};
// Off without a map (or with normals shading, which ignores light).
EnvironmentShading environment_shading(const RenderSettings& s);

// The environment map behind everything: a float texture (uploaded when the map changes) read
// along each pixel's ray.
class EnvironmentPass {
 public:
  explicit EnvironmentPass(const GlFunctions& gl);
  ~EnvironmentPass();
  EnvironmentPass(const EnvironmentPass&) = delete;
  EnvironmentPass& operator=(const EnvironmentPass&) = delete;

  // Into the bound framebuffer, without depth; s.environment.map must be set.
  void draw(const RenderSettings& s, const Eigen::Matrix4f& view_projection);

 private:
  void bind_map(const std::shared_ptr<const EnvironmentMap>& map);

  const GlFunctions& m_gl;
  GlProgram m_program;
  GLuint m_texture = 0, m_empty_vao = 0;
  std::shared_ptr<const EnvironmentMap> m_map;  // what m_texture holds
};

// The shadow map and the depth-only program that draws it.
class ShadowPass {
 public:
  explicit ShadowPass(const GlFunctions& gl);
  ~ShadowPass();
  ShadowPass(const ShadowPass&) = delete;
  ShadowPass& operator=(const ShadowPass&) = delete;

  // Draws the casters' depth (each mesh's first `count` indices; 0: skipped) through
  // light_matrix; the map is created on first use.
  void draw(const Eigen::Matrix4f& light_matrix,
            const std::vector<std::pair<const MeshBuffers*, GLsizei>>& casters);
  GLuint depth_texture() const { return m_depth; }

 private:
  void ensure_map();

  const GlFunctions& m_gl;
  GlProgram m_program;
  GLuint m_fbo = 0, m_depth = 0;
};

// The ground square, drawn from gl_VertexID, with and without the shadow lookup.
class GroundPass {
 public:
  explicit GroundPass(const GlFunctions& gl);
  ~GroundPass();
  GroundPass(const GroundPass&) = delete;
  GroundPass& operator=(const GroundPass&) = delete;

  // Into the bound framebuffer. shadow_matrix: the light's view-projection when there is a
  // shadow (shadow_map then holds the casters' depth), and footprint the casters' shadow in
  // its clip x, y (caster_footprint).
  // `environment` replaces the ambient light when on.
  void draw(const RenderSettings& s, const Eigen::Matrix4f& view_projection,
            const Eigen::Matrix4f* shadow_matrix, const Eigen::AlignedBox2d& footprint,
            GLuint shadow_map, const EnvironmentShading& environment);

 private:
  void set_uniforms(const GlProgram& p, const RenderSettings& s,
                    const Eigen::Matrix4f& view_projection, const Eigen::Matrix4f* shadow_matrix,
                    const EnvironmentShading& environment) const;

  const GlFunctions& m_gl;
  GlProgram m_shadowed, m_unshadowed;
  GLuint m_empty_vao = 0;  // the ground needs no attributes
};

// Lit (or normals-shaded) surfaces: the cloth program with its uniforms set, then one draw per
// index range with its front and back colours; the cloth's texture on texture unit 1.
class SurfacePass {
 public:
  explicit SurfacePass(const GlFunctions& gl);
  ~SurfacePass();
  SurfacePass(const SurfacePass&) = delete;
  SurfacePass& operator=(const SurfacePass&) = delete;

  // Uses the program with the frame's camera and light (`environment` replacing the ambient
  // light when on); binds the cloth texture (uploading it when the image changed) when
  // `textured`, placed on the material by `texture_placement` (render/texture.h).
  void begin(const RenderSettings& s, const Eigen::Matrix4f& view_projection, bool textured,
             const TexturePlacement& texture_placement, const EnvironmentShading& environment);
  // `cloth`: the range is the cloth, which gets its sheen (render/sheen.h) and weave
  // (render/weave.h).
  void draw(const MeshBuffers& b, std::size_t first_index, GLsizei index_count,
            const Eigen::Vector3f& front, const Eigen::Vector3f& back, bool cloth = false,
            bool textured = false,
            bool vertex_coloured = false);  // the vertex colours on both sides

 private:
  // A GL texture holding an image, uploaded again only when the image changes.
  struct ImageTexture {
    GLuint name = 0;                     // created on first use
    const Image* image = nullptr;        // what it holds (compared by address)
    std::shared_ptr<const Image> owner;  // keeps that address valid
  };
  // Binds `image` to texture unit `unit` (mipmapped, repeating or clamped), uploading it first
  // when `texture` holds another.
  void bind_image(ImageTexture& texture, const std::shared_ptr<const Image>& image, GLenum unit,
                  bool repeat);

  const GlFunctions& m_gl;
  GlProgram m_program;
  ImageTexture m_texture;  // the cloth's texture, unit 1
  ImageTexture m_weave;    // the weave's normal map, unit 2
};

}  // namespace weft::render::detail
