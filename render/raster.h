#pragma once
// OpenGL 3.3 core rasterizer: draws a RenderMesh off-screen into an Image.

#include <memory>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/cloth_surface.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/render_mesh.h"
#include "render/raytrace/raytrace_settings.h"

namespace weft::render {

enum class Shading { lit, normals };  // normals: |n| as colour (seed 003's debug view)

// Which renderer draws the frames (render/renderer.h): the OSMesa rasterizer or the Embree
// ray tracer.
enum class RendererKind { raster, raytrace };

struct RenderSettings {
  int width = 640, height = 480;
  Camera camera;
  Eigen::Vector3d light_direction{0.4, -0.6, 1.0};  // towards the key light, need not be unit
  double light_intensity = 0.85;                    // key light, diffuse
  double ambient = 0.25;
  Eigen::Vector3f front_color{0.80f, 0.25f, 0.20f};  // linear 0..1
  Eigen::Vector3f back_color{0.25f, 0.45f, 0.80f};   // back faces get their own colour
  Eigen::Vector3f background{0.92f, 0.93f, 0.95f};
  bool ground = true;
  double ground_z_m = 0.0;
  double ground_half_size_m = 5.0;
  Eigen::Vector3f ground_color{0.60f, 0.60f, 0.58f};
  // Colour app/ gives obstacles (RenderObject::color); the renderer itself does not read it.
  Eigen::Vector3f obstacle_color{0.70f, 0.74f, 0.80f};
  Shading shading = Shading::lit;
  int msaa_samples = 4;
  RendererKind renderer = RendererKind::raster;
  // The rasterizer's GL context (gl_context.h): auto, osmesa or egl; WEFT_GL overrides it.
  GlBackend gl = GlBackend::automatic;
  RayTraceSettings raytrace;  // read by the ray tracer only
  // Subdivision, thickness shell and texture of the cloth (render/cloth_surface.h): the mesh
  // aids are applied by the Renderer interface (renderer.h), the texture by each renderer.
  ClothSurface cloth_surface;
};

// Bad input: throws std::invalid_argument naming the field ("RenderSettings: ...") unless the
// settings can be drawn; max_size is the largest width or height the renderer supports.
void validate(const RenderSettings& settings, int max_size);

// An opaque object drawn with the cloth (e.g. an obstacle): lit like the cloth's front side,
// in one colour on both sides, depth-tested against the cloth and the other objects, and
// casting a shadow on the ground as the cloth does.
struct RenderObject {
  RenderMesh mesh;                             // normals computed when missing
  Eigen::Vector3f color{0.70f, 0.74f, 0.80f};  // linear 0..1; the default obstacle_color
};

class RasterRenderer {
 public:
  // Takes ownership of a context; allocates GL resources lazily for each image size.
  explicit RasterRenderer(std::unique_ptr<GlContext> context);
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  // The cloth alone: render(mesh, settings, {}).
  Image render(const RenderMesh& mesh, const RenderSettings& settings);
  // The cloth and extra opaque objects. Throws std::invalid_argument for bad settings or a bad
  // mesh (an object's message starts "object k: ").
  Image render(const RenderMesh& cloth, const RenderSettings& settings,
               const std::vector<RenderObject>& objects);
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace weft::render
