// OpenGL 3.3 core rasterizer. Per render():
//   1. validate the settings and the meshes (computing vertex normals on a copy if missing);
//      the extra objects are merged into one mesh, drawn range by range in their colours,
//   2. upload positions, normals and triangles of the cloth and of the objects (the cloth
//      changes every frame),
//   3. shadow pass (ground on, lit): cloth and object depth from the key light, orthographic,
//   4. main pass into a multisampled FBO: clear to the background (or draw the environment map
//      there), ground pass, surface pass (cloth, objects) — the passes are in raster_passes.h,
//   5. resolve (glBlitFramebuffer) into a single-sample FBO, glFinish, glReadPixels,
//      and flip rows so that Image row 0 is the top (raster_gl.h's RenderTargets).
// GL entry points come from the GlContext (gl_functions.h); nothing links GL directly.

#include "render/raster.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/gl_functions.h"
#include "render/raster_gl.h"
#include "render/raster_passes.h"
#include "render/strain_colour.h"

namespace weft::render {

namespace {

using detail::check_gl_error;
using detail::EnvironmentPass;
using detail::EnvironmentShading;
using detail::GlFunctions;
using detail::GroundPass;
using detail::MeshBuffers;
using detail::RenderTargets;
using detail::ShadowPass;
using detail::SurfacePass;
using detail::caster_footprint;
using detail::light_view_projection;
using detail::load_gl_functions;
using detail::shadow_map_size;

// `context`, made current; throws std::invalid_argument when there is none.
std::unique_ptr<GlContext> current_context(std::unique_ptr<GlContext> context) {
  if (!context) throw std::invalid_argument("RasterRenderer: no GL context given");
  context->make_current();
  return context;
}

GLint gl_integer(const GlFunctions& gl, GLenum name) {
  GLint value = 0;
  gl.GetIntegerv(name, &value);
  return value;
}

// Bad input in the mesh (validate, render_mesh.h), and at most INT_MAX/3 triangles (one draw
// call). Messages start with `name` ("RenderMesh", "object 2").
void validate_for_gl(const RenderMesh& mesh, const std::string& name = "RenderMesh") {
  validate(mesh, name);
  if (mesh.triangles.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max() / 3)) {
    throw std::invalid_argument(name + ": too many triangles for one draw call");
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

// One frame's meshes as the passes draw them: the cloth with vertex normals (a copy when they
// were missing) and all objects merged into one mesh; index counts, 3 per triangle.
struct FrameMeshes {
  RenderMesh cloth_storage;
  const RenderMesh* cloth = nullptr;
  RenderMesh objects;
  std::vector<ObjectRange> ranges;  // of each object in `objects`
  GLsizei cloth_count = 0, object_count = 0;
};

// Step 1: validated (bad input throws std::invalid_argument naming the mesh).
void prepare_meshes(const RenderMesh& cloth, const std::vector<RenderObject>& objects,
                    FrameMeshes& m) {
  validate_for_gl(cloth);
  // Vertex normals are required; computed on a copy when missing or stale in size.
  m.cloth = &with_normals(cloth, m.cloth_storage);
  m.objects = merge_objects(objects, m.ranges);
  m.cloth_count = static_cast<GLsizei>(3 * m.cloth->triangles.size());
  m.object_count = static_cast<GLsizei>(3 * m.objects.triangles.size());
}

// The mask pass (render_mask): the same frame drawn unlit and flat — counted surfaces white,
// the others and the background black, one sample per pixel (its centre, as the ray tracer's
// mask) — so that a pixel is set when its colour is at least half white. The ground's grid
// lines darken it by at most 16 % and its rim fades into the background with the ray tracer's
// smoothstep, so its threshold crossing is the ray tracer's r = 0.8.
RenderSettings mask_settings(const RenderSettings& s, bool cloth_only) {
  const Eigen::Vector3f white = Eigen::Vector3f::Ones(), black = Eigen::Vector3f::Zero();
  RenderSettings m = s;
  m.shading = Shading::lit;
  m.light_intensity = 0.0;
  m.ambient = 1.0;
  m.front_color = white;
  m.back_color = std::nullopt;
  m.background = black;
  m.ground_color = cloth_only ? black : white;
  m.msaa_samples = 1;
  m.cloth_surface.texture.image = nullptr;
  m.cloth_surface.sheen = 0.0;
  m.cloth_surface.weave = Weave{};
  m.environment = Environment{};  // no image-based light or background: geometry only
  return m;
}

Mask bright_pixels(const Image& image) {
  Mask mask(image.width(), image.height());
  const std::uint8_t* rgb = image.data();
  for (std::size_t i = 0; i < mask.in.size(); ++i)
    mask.in[i] = std::max({rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]}) >= 128;
  return mask;
}

}  // namespace

struct RasterRenderer::Impl {
  explicit Impl(std::unique_ptr<GlContext> context);
  // The context is made current first: the members release their GL names in it.
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects);
  std::string description() const { return m_context->description(); }

 private:
  // Steps 3 and 4: the shadow map when there is a shadow (returns whether there is), the
  // environment map behind, the ground and the surfaces into the render targets.
  bool draw_shadow(const RenderSettings& s, const FrameMeshes& m, Eigen::Matrix4f& light_matrix,
                   Eigen::AlignedBox2d& footprint);
  void draw_main_pass(const RenderSettings& s, const FrameMeshes& m,
                      const Eigen::Matrix4f* light_matrix, const Eigen::AlignedBox2d& footprint);

  std::unique_ptr<GlContext> m_context;  // declared first: destroyed after the GL objects
  GlFunctions m_gl;
  GLint m_max_samples = 0, m_max_size = 0;
  // The GL objects, created in this order and released in the reverse one.
  SurfacePass m_surface;
  GroundPass m_ground;
  EnvironmentPass m_environment;
  ShadowPass m_shadow;
  MeshBuffers m_cloth, m_objects;
  RenderTargets m_targets;
};

RasterRenderer::Impl::Impl(std::unique_ptr<GlContext> context)
    : m_context(current_context(std::move(context))),
      m_gl(load_gl_functions(*m_context)),
      m_max_samples(gl_integer(m_gl, GL_MAX_SAMPLES)),
      m_max_size(gl_integer(m_gl, GL_MAX_RENDERBUFFER_SIZE)),
      m_surface(m_gl),
      m_ground(m_gl),
      m_environment(m_gl),
      m_shadow(m_gl),
      m_cloth(m_gl),
      m_objects(m_gl),
      m_targets(m_gl) {
  check_gl_error(m_gl, "RasterRenderer setup");
}

RasterRenderer::Impl::~Impl() {
  try {
    m_context->make_current();
  } catch (...) {
    // The context is going away with everything it holds; nothing more to do.
  }
}

bool RasterRenderer::Impl::draw_shadow(const RenderSettings& s, const FrameMeshes& m,
                                       Eigen::Matrix4f& light_matrix,
                                       Eigen::AlignedBox2d& footprint) {
  const Eigen::Vector3d light_unit = s.light_direction.normalized();
  const bool shadow = s.ground && s.shading == Shading::lit &&
                      m.cloth_count + m.object_count > 0 && light_unit.z() > 1e-6 &&
                      s.light_intensity > 0.0;
  if (!shadow) return false;
  light_matrix = light_view_projection({m.cloth, &m.objects}, light_unit);
  m_shadow.draw(light_matrix, {{&m_cloth, m.cloth_count}, {&m_objects, m.object_count}});
  // Beyond the PCF's reach (±3 texels, bilinear: under 5) of every caster texel.
  footprint = caster_footprint({m.cloth, &m.objects}, light_matrix, 8.0 * 2.0 / shadow_map_size);
  return true;
}

void RasterRenderer::Impl::draw_main_pass(const RenderSettings& s, const FrameMeshes& m,
                                          const Eigen::Matrix4f* light_matrix,
                                          const Eigen::AlignedBox2d& footprint) {
  const Eigen::Matrix4f view_projection =
      s.camera.projection_matrix(s.width, s.height) * s.camera.view_matrix();
  m_targets.bind_for_drawing();
  m_gl.Enable(GL_MULTISAMPLE);
  m_gl.DepthMask(GL_TRUE);
  m_gl.ClearColor(s.background.x(), s.background.y(), s.background.z(), 1.0f);
  m_gl.ClearDepth(1.0);
  m_gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m_gl.Enable(GL_DEPTH_TEST);
  m_gl.DepthFunc(GL_LESS);
  m_gl.Disable(GL_CULL_FACE);  // two-sided cloth
  check_gl_error(m_gl, "starting the main pass");
  const EnvironmentShading environment = detail::environment_shading(s);
  if (environment.on && environment.background) m_environment.draw(s, view_projection);
  if (s.ground) {
    m_ground.draw(s, view_projection, light_matrix, footprint, m_shadow.depth_texture(),
                  environment);
  }
  if (m.cloth_count + m.object_count == 0) return;
  const bool textured =
      s.cloth_surface.texture.image && m.cloth->uvs.size() == m.cloth->positions.size();
  const TexturePlacement placement =
      textured ? texture_placement(s.cloth_surface.texture, m.cloth->uvs) : TexturePlacement{};
  m_surface.begin(s, view_projection, textured, placement, environment);
  if (m.cloth_count > 0)
    m_surface.draw(m_cloth, 0, m.cloth_count, s.front_color, back_side_color(s), true, textured,
                   s.shading == Shading::strain);
  for (const ObjectRange& r : m.ranges) {
    if (r.index_count > 0) m_surface.draw(m_objects, r.first_index, r.index_count, r.color, r.color);
  }
}

Image RasterRenderer::Impl::render(const RenderMesh& cloth_input, const RenderSettings& s,
                                   const std::vector<RenderObject>& objects) {
  m_context->make_current();
  validate(s, m_max_size);
  validate(s.cloth_surface);
  FrameMeshes m;
  prepare_meshes(cloth_input, objects, m);

  const int samples = s.msaa_samples <= 1 ? 0 : std::min(s.msaa_samples, int{m_max_samples});
  m_targets.ensure(s.width, s.height, samples);
  if (m.cloth_count > 0)
    m_cloth.upload(*m.cloth, s.shading == Shading::strain
                                 ? strain_colours(*m.cloth, static_cast<float>(s.strain_full_scale))
                                 : std::vector<Eigen::Vector3f>{});
  if (m.object_count > 0) m_objects.upload(m.objects);

  Eigen::Matrix4f light_matrix = Eigen::Matrix4f::Identity();
  Eigen::AlignedBox2d footprint;  // of the casters' shadow, light clip x, y
  const bool shadow = draw_shadow(s, m, light_matrix, footprint);
  draw_main_pass(s, m, shadow ? &light_matrix : nullptr, footprint);
  return m_targets.read_back();
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

Mask RasterRenderer::render_mask(const RenderMesh& cloth, const RenderSettings& settings,
                                 const std::vector<RenderObject>& objects, bool cloth_only) {
  std::vector<RenderObject> flat = objects;
  for (RenderObject& object : flat)
    object.color = cloth_only ? Eigen::Vector3f::Zero() : Eigen::Vector3f::Ones();
  return bright_pixels(m_impl->render(cloth, mask_settings(settings, cloth_only), flat));
}

std::string RasterRenderer::description() const {
  return m_impl->description();
}

}  // namespace weft::render
