// Embree ray tracer. Per render():
//   1. validate the settings (RenderSettings and its raytrace part) and the meshes, computing
//      vertex normals on a copy where missing,
//   2. bring the Embree scene up to date: the cloth's geometry is kept while its triangles
//      stay the same (only the vertex buffer is rewritten), objects likewise, the ground is a
//      square under the camera target as the rasterizer's; commit (BVH build, one thread),
//   3. a FrameView of the camera, lights and surfaces (integrator.h),
//   4. the pool's threads (base/thread_pool.h) take 16×16 tiles in order and sample their
//      pixels — with adaptive sampling in two passes, the second deciding each pixel's samples
//      from the first pass's denoised image (adaptive_sampling.h) — then the denoiser and the
//      bytes; a pixel's samples depend on its own index and the first pass only, so the image is
//      the same for any thread count.

#include "render/raytrace/ray_tracer.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/constants.h"
#include "base/thread_pool.h"
#include "render/denoise.h"
#include "render/environment.h"
#include "render/primitives.h"
#include "render/raytrace/embree_scene.h"
#include "render/raytrace/integrator.h"
#include "render/raytrace/shading.h"
#include "render/strain_colour.h"

namespace weft::render {

namespace {

constexpr int max_image_side = 16384;
constexpr int tile_side = 16;

void validate_raytrace(const RayTraceSettings& r) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RenderSettings: raytrace." + what);
  };
  if (r.samples_per_pixel < 1 || r.samples_per_pixel > 65536)
    fail("samples_per_pixel must be in 1..65536, got " + std::to_string(r.samples_per_pixel));
  if (!(r.adaptive_error >= 0.0 && r.adaptive_error <= 255.0))
    fail("adaptive_error must be in [0, 255] display levels");
  if (r.adaptive_round < 1 || r.adaptive_round > 65536)
    fail("adaptive_round must be in 1..65536, got " + std::to_string(r.adaptive_round));
  if (r.bounces < 0 || r.bounces > 64)
    fail("bounces must be in 0..64, got " + std::to_string(r.bounces));
  if (r.ao_samples < 0 || r.ao_samples > 1024)
    fail("ao_samples must be in 0..1024, got " + std::to_string(r.ao_samples));
  if (!(r.ao_distance_m > 0.0) || !std::isfinite(r.ao_distance_m))
    fail("ao_distance_m must be finite and > 0");
  if (!(r.sun_angular_radius_deg >= 0.0 && r.sun_angular_radius_deg <= 45.0))
    fail("sun_angular_radius_deg must be in [0, 45]");
  if (r.threads < 0 || r.threads > 4096)
    fail("threads must be in 0..4096 (0: all hardware threads), got " + std::to_string(r.threads));
}

// Threads for the tiles: the setting (0: all hardware threads), at most one per tile.
int thread_count(const RayTraceSettings& r, int tiles) {
  return static_cast<int>(std::clamp<std::size_t>(base::thread_count(r.threads), 1,
                                                  static_cast<std::size_t>(std::max(tiles, 1))));
}

float max_abs_coordinate(const RenderMesh& mesh) {
  float m = 0.0f;
  for (const Eigen::Vector3f& p : mesh.positions) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

// The meshes of one frame as the ray tracer draws them: validated, with vertex normals (copies
// where they were missing), and the ground square under the camera target as the rasterizer's.
struct FrameMeshes {
  RenderMesh cloth_storage;
  const RenderMesh* cloth = nullptr;
  std::vector<RenderMesh> object_storage;
  std::vector<const RenderMesh*> objects;
  RenderMesh ground;  // empty without a ground
  std::vector<Eigen::Vector3f> cloth_colours;  // Shading::strain: the cloth's false colours
};

// Step 1 (validate_raytrace and validate(RenderSettings) are checked before).
void prepare_meshes(const RenderMesh& cloth, const RenderSettings& s,
                    const std::vector<RenderObject>& objects, FrameMeshes& m) {
  validate(cloth);
  m.cloth = &with_normals(cloth, m.cloth_storage);
  m.object_storage.resize(objects.size());
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const std::string name = "object " + std::to_string(k);
    validate(objects[k].mesh, name);
    if (!objects[k].color.allFinite()) throw std::invalid_argument(name + ": colour is not finite");
    m.objects.push_back(&with_normals(objects[k].mesh, m.object_storage[k]));
  }
  if (s.shading == Shading::strain)
    m.cloth_colours = strain_colours(*m.cloth, static_cast<float>(s.strain_full_scale));
  if (s.ground) {
    m.ground =
        make_square_patch(Eigen::Vector3d(s.camera.target.x(), s.camera.target.y(), s.ground_z_m),
                          Eigen::Vector3d::UnitZ(), s.ground_half_size_m);
  }
}

// Step 3, the camera: Camera::view_matrix's basis (which also checks eye, target and up) and
// its projection's extent and principal point (which checks fov or intrinsics, near, far).
void set_camera(const Camera& camera, int width, int height, rt::FrameView& view) {
  view.width = width;
  view.height = height;
  const Eigen::Matrix4f view_matrix = camera.view_matrix();
  const Eigen::Matrix4f projection = camera.projection_matrix(width, height);
  const Eigen::Vector3f side = view_matrix.block<1, 3>(0, 0).transpose();
  const Eigen::Vector3f true_up = view_matrix.block<1, 3>(1, 0).transpose();
  view.forward = -view_matrix.block<1, 3>(2, 0).transpose();
  // At depth 1 the image spans ±1/P(0,0) sideways and ±1/P(1,1) up and down about the
  // principal point, which lies at NDC (−P(0,2), −P(1,2)) (zero for a look-at camera).
  view.right = side / projection(0, 0);
  view.up = true_up / projection(1, 1);
  if (camera.intrinsics) view.forward += projection(0, 2) * view.right + projection(1, 2) * view.up;
  view.eye = camera.eye.cast<float>();
  view.near_m = static_cast<float>(camera.near_m);
  view.far_m = static_cast<float>(camera.far_m);
  view.pixel_angle = 2.0f / (projection(1, 1) * static_cast<float>(height));
}

// Step 3, light, ground and sampling.
void set_lighting(const RenderSettings& s, rt::FrameView& view) {
  view.shading = s.shading;
  view.sun = s.light_direction.normalized().cast<float>();
  view.sun_cos_max = static_cast<float>(std::cos(base::deg_to_rad(s.raytrace.sun_angular_radius_deg)));
  view.sun_intensity = static_cast<float>(s.light_intensity);
  view.sky = static_cast<float>(s.ambient);
  view.background = rt::reflectance_from_color(s.background);
  // Normals shading ignores light and shows the background colour, as the rasterizer's.
  if (s.environment.map && s.shading == Shading::lit) view.environment.emplace(s.environment);
  view.environment_background = s.environment.background;
  view.ground = s.ground;
  view.ground_center =
      Eigen::Vector3d(s.camera.target.x(), s.camera.target.y(), s.ground_z_m).cast<float>();
  view.ground_half_size_m = static_cast<float>(s.ground_half_size_m);
  view.samples_per_pixel = s.raytrace.samples_per_pixel;
  view.adaptive.max_error = static_cast<float>(s.raytrace.adaptive_error);
  view.adaptive.round_samples = s.raytrace.adaptive_round;
  view.bounces = s.raytrace.bounces;
  view.ao_samples = s.raytrace.ao_samples;
  view.ao_distance_m = static_cast<float>(s.raytrace.ao_distance_m);
  view.sheen = static_cast<float>(s.cloth_surface.sheen);
  view.sheen_roughness = static_cast<float>(s.cloth_surface.sheen_roughness);
  view.seed = s.raytrace.seed;
}

// The denoiser's input from the pixels' samples so far.
DenoiseInput denoise_input(const std::vector<rt::PixelState>& pixels, int width, int height) {
  DenoiseInput in;
  in.width = width;
  in.height = height;
  const std::size_t n = pixels.size();
  in.radiance.resize(n);
  in.normal.resize(n);
  in.albedo.resize(n);
  in.depth_m.resize(n);
  in.coverage.resize(n);
  in.variance.resize(n);
  in.mixed.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const rt::PixelGuide g = pixels[p].guide();
    in.radiance[p] = pixels[p].samples.mean();
    in.normal[p] = g.normal;
    in.albedo[p] = g.albedo;
    in.depth_m[p] = g.depth_m;
    in.coverage[p] = g.coverage;
    in.variance[p] = g.variance;
    in.mixed[p] = g.mixed ? 1 : 0;
  }
  return in;
}

// The 16×16 tiles of an image, run by the pool's threads in order, one task per tile; the
// exception of the lowest failing tile is rethrown. Rays are counted per tile.
class Tiles {
 public:
  Tiles(int width, int height, base::ThreadPool& pool)
      : m_width(width), m_height(height), m_x((width + tile_side - 1) / tile_side),
        m_y((height + tile_side - 1) / tile_side), m_pool(pool),
        m_counts(static_cast<std::size_t>(m_x * m_y)) {}
  int count() const { return m_x * m_y; }
  // pixel(x, y, counts) for every pixel, tile by tile; then done(), one call at a time.
  template <class Pixel, class Done>
  void run(const Pixel& pixel, const Done& done) {
    std::mutex mutex;
    m_pool.run(m_counts.size(), [&](std::size_t k) {
      const int tile = static_cast<int>(k);
      const int x0 = (tile % m_x) * tile_side, y0 = (tile / m_x) * tile_side;
      const int x1 = std::min(x0 + tile_side, m_width), y1 = std::min(y0 + tile_side, m_height);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) pixel(x, y, m_counts[k]);
      const std::lock_guard<std::mutex> lock(mutex);
      done();
    });
  }
  RayCounts total() const {  // summed in tile order
    RayCounts t;
    for (const RayCounts& c : m_counts) {
      t.camera += c.camera;
      t.shadow += c.shadow;
      t.occlusion += c.occlusion;
      t.bounce += c.bounce;
    }
    return t;
  }

 private:
  int m_width, m_height, m_x, m_y;
  base::ThreadPool& m_pool;
  std::vector<RayCounts> m_counts;
};

// Adaptive sampling's decision (render/raytrace/adaptive_sampling.h): the samples each pixel
// takes in all, from the first pass's pixels and, when denoising, the variance left after
// filtering them.
std::vector<int> samples_needed(const rt::FrameView& view, const std::vector<rt::PixelState>& pixels,
                                const DenoiseInput* in, const std::vector<Eigen::Vector3f>& denoised,
                                const std::vector<float>& filtered_variance) {
  std::vector<int> needed(pixels.size());
  for (std::size_t p = 0; p < pixels.size(); ++p) {
    const rt::PixelSamples& samples = pixels[p].samples;
    float mean = samples.luminance_mean(), error = samples.luminance_standard_error();
    if (in && denoised_pixel(*in, p)) {
      const Eigen::Vector3f albedo = in->albedo[p].cwiseMax(Eigen::Vector3f::Constant(1e-3f));
      mean = static_cast<float>(luminance(denoised[p]));
      error = std::sqrt(filtered_variance[p]) * static_cast<float>(luminance(albedo));
    }
    needed[p] = rt::samples_needed(samples.count(), rt::display_error(mean, error),
                                   view.adaptive.max_error, view.samples_per_pixel);
  }
  return needed;
}

// Step 4: the pool's threads take the tiles (Tiles) and sample their pixels: samples_per_pixel
// each, or with adaptive sampling a first pass of round_samples and a second pass for the
// pixels that need more. The bytes go into `image` — through the denoiser (render/denoise.h)
// when the settings ask. Returns the rays traced. `pool` is made (again) when it does not have
// the threads the settings ask for. `progress` (when set) hears the share of tiles done (both
// passes' tiles, with adaptive sampling) after each tile, one call at a time.
RayCounts trace_tiles(const rt::FrameView& view, const RayTraceSettings& r, Image& image,
                      std::unique_ptr<base::ThreadPool>& pool,
                      const std::function<void(double)>& progress) {
  const int width = image.width(), height = image.height();
  const int threads = thread_count(r, ((width + tile_side - 1) / tile_side) *
                                          ((height + tile_side - 1) / tile_side));
  if (!pool || pool->size() != static_cast<std::size_t>(threads))
    pool = std::make_unique<base::ThreadPool>(threads);
  Tiles tiles(width, height, *pool);
  // Noise-free shading (normals) and single samples have nothing to denoise.
  const bool denoised = r.denoise && view.samples_per_pixel > 1 && view.shading != Shading::normals;
  const int first = view.adaptive.max_error > 0.0f
                        ? std::min(view.samples_per_pixel, std::max(view.adaptive.round_samples, 1))
                        : view.samples_per_pixel;
  const int passes = first < view.samples_per_pixel ? 2 : 1;
  int tiles_done = 0;
  const auto tile_done = [&] {
    if (progress) progress(static_cast<double>(++tiles_done) / (passes * tiles.count()));
  };
  std::vector<rt::PixelState> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  tiles.run([&](int x, int y, RayCounts& counts) {
    rt::add_pixel_samples(view, x, y, first, pixels[static_cast<std::size_t>(y) * width + x], counts);
  }, tile_done);
  std::vector<float> filtered_variance;
  DenoiseInput in;
  std::vector<Eigen::Vector3f> radiance;
  if (denoised) {
    in = denoise_input(pixels, width, height);
    radiance = denoise(in, DenoiseSettings{}, pool.get(), &filtered_variance);
  }
  if (passes == 2) {
    const std::vector<int> needed =
        samples_needed(view, pixels, denoised ? &in : nullptr, radiance, filtered_variance);
    tiles.run([&](int x, int y, RayCounts& counts) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      rt::add_pixel_samples(view, x, y, needed[p] - pixels[p].samples.count(), pixels[p], counts);
    }, tile_done);
    if (denoised) {
      in = denoise_input(pixels, width, height);
      radiance = denoise(in, DenoiseSettings{}, pool.get());
    }
  }
  std::uint8_t* const bytes = image.data();
  for (std::size_t p = 0; p < pixels.size(); ++p) {
    const Eigen::Vector3f value = denoised ? radiance[p] : pixels[p].samples.mean();
    for (int c = 0; c < 3; ++c) bytes[3 * p + c] = rt::encode_channel(value[c]);
  }
  return tiles.total();
}

}  // namespace

struct RayTracer::Impl {
  rt::EmbreeDevice device;  // declared first: released last
  rt::EmbreeScene scene{device, RTC_BUILD_QUALITY_HIGH};
  rt::TriangleGeometry cloth_geometry, ground_geometry;
  std::vector<std::unique_ptr<rt::TriangleGeometry>> object_geometries;
  RayCounts last_counts;
  std::unique_ptr<base::ThreadPool> pool;  // the tiles' threads, kept from frame to frame
  std::function<void(double)> progress;    // hears the tiles done (set_frame_progress)

  Image render(const RenderMesh& cloth, const RenderSettings& s,
               const std::vector<RenderObject>& objects);
  Mask render_mask(const RenderMesh& cloth, const RenderSettings& s,
                   const std::vector<RenderObject>& objects, bool cloth_only);
  // Steps 1 to 3 of render().
  rt::FrameView prepare(const RenderMesh& cloth, const RenderSettings& s,
                        const std::vector<RenderObject>& objects, FrameMeshes& meshes);
  // Step 2: the Embree scene, committed.
  void update_scene(const FrameMeshes& m);
  // Step 3: what the pixels read (scene, surfaces, camera, light; integrator.h).
  rt::FrameView frame_view(const FrameMeshes& m, const RenderSettings& s,
                           const std::vector<RenderObject>& objects) const;
};

void RayTracer::Impl::update_scene(const FrameMeshes& m) {
  cloth_geometry.set(device, scene, m.cloth->positions, m.cloth->triangles);
  ground_geometry.set(device, scene, m.ground.positions, m.ground.triangles);
  while (object_geometries.size() < m.objects.size())
    object_geometries.push_back(std::make_unique<rt::TriangleGeometry>());
  object_geometries.resize(m.objects.size());  // released ones detach themselves
  for (std::size_t k = 0; k < m.objects.size(); ++k)
    object_geometries[k]->set(device, scene, m.objects[k]->positions, m.objects[k]->triangles);
  scene.commit(device);
}

rt::FrameView RayTracer::Impl::frame_view(const FrameMeshes& m, const RenderSettings& s,
                                          const std::vector<RenderObject>& objects) const {
  rt::FrameView view;
  view.scene = scene.get();
  const auto add_surface = [&](const rt::TriangleGeometry& g, rt::SurfaceShading surface) {
    if (!g.attached()) return;
    if (view.surfaces.size() <= g.id()) view.surfaces.resize(g.id() + 1);
    view.surfaces[g.id()] = surface;
  };
  float extent = std::max(max_abs_coordinate(*m.cloth), max_abs_coordinate(m.ground));
  rt::SurfaceShading cloth{m.cloth, rt::reflectance_from_color(s.front_color),
                           rt::reflectance_from_color(back_side_color(s)), true, false};
  if (const ClothTexture& texture = s.cloth_surface.texture; texture.image) {
    cloth.texture = texture.image.get();
    cloth.texture_placement = texture_placement(texture, m.cloth->uvs);
    cloth.texture_back = texture_on_back(s);
  }
  if (!m.cloth_colours.empty()) cloth.vertex_colours = &m.cloth_colours;
  else if (s.cloth_surface.weave.normal_map && s.shading == Shading::lit)
    cloth.weave = &s.cloth_surface.weave;
  add_surface(cloth_geometry, cloth);
  const Eigen::Vector3f ground_reflectance = rt::reflectance_from_color(s.ground_color);
  add_surface(ground_geometry, {&m.ground, ground_reflectance, ground_reflectance, false, true});
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const Eigen::Vector3f reflectance = rt::reflectance_from_color(objects[k].color);
    add_surface(*object_geometries[k], {m.objects[k], reflectance, reflectance, false, false});
    extent = std::max(extent, max_abs_coordinate(*m.objects[k]));
  }
  set_camera(s.camera, s.width, s.height, view);
  extent = std::max(extent, view.eye.cwiseAbs().maxCoeff());
  set_lighting(s, view);
  // Float positions near `extent` are exact to ~6e-8 extent; Embree's hits to a few ulps more.
  view.epsilon_m = 2e-5f * (1.0f + extent);
  return view;
}

rt::FrameView RayTracer::Impl::prepare(const RenderMesh& cloth, const RenderSettings& s,
                                       const std::vector<RenderObject>& objects,
                                       FrameMeshes& meshes) {
  validate(s, max_image_side);
  validate_raytrace(s.raytrace);
  validate(s.cloth_surface);
  prepare_meshes(cloth, s, objects, meshes);
  update_scene(meshes);
  return frame_view(meshes, s, objects);
}

Image RayTracer::Impl::render(const RenderMesh& cloth, const RenderSettings& s,
                              const std::vector<RenderObject>& objects) {
  FrameMeshes meshes;
  const rt::FrameView view = prepare(cloth, s, objects, meshes);
  Image image(s.width, s.height);
  last_counts = trace_tiles(view, s.raytrace, image, pool, progress);
  return image;
}

// One camera ray per pixel centre, rows shared among the pool's threads.
Mask RayTracer::Impl::render_mask(const RenderMesh& cloth, const RenderSettings& s,
                                  const std::vector<RenderObject>& objects, bool cloth_only) {
  FrameMeshes meshes;
  const rt::FrameView view = prepare(cloth, s, objects, meshes);
  const rt::SurfaceShading* const cloth_surface =
      cloth_geometry.attached() ? &view.surfaces[cloth_geometry.id()] : nullptr;
  Mask mask(s.width, s.height);
  const int threads = thread_count(s.raytrace, s.height);
  if (!pool || pool->size() != static_cast<std::size_t>(threads))
    pool = std::make_unique<base::ThreadPool>(threads);
  pool->run(static_cast<std::size_t>(s.height), [&](std::size_t row) {
    const int y = static_cast<int>(row);
    for (int x = 0; x < s.width; ++x) {
      const rt::SurfaceShading* seen = rt::visible_surface(view, x, y);
      mask.set(x, y, cloth_only ? seen != nullptr && seen == cloth_surface : seen != nullptr);
    }
  });
  return mask;
}

RayTracer::RayTracer() : m_impl(std::make_unique<Impl>()) {}
RayTracer::~RayTracer() = default;

Image RayTracer::render(const RenderMesh& cloth, const RenderSettings& settings,
                        const std::vector<RenderObject>& objects) {
  return m_impl->render(cloth, settings, objects);
}

Mask RayTracer::render_mask(const RenderMesh& cloth, const RenderSettings& settings,
                           const std::vector<RenderObject>& objects, bool cloth_only) {
  return m_impl->render_mask(cloth, settings, objects, cloth_only);
}

std::string RayTracer::description() const {
  return "Embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) +
         "." + std::to_string(RTC_VERSION_PATCH) + " ray tracer";
}

void RayTracer::set_frame_progress(std::function<void(double done)> progress) {
  m_impl->progress = std::move(progress);
}

RayCounts RayTracer::last_ray_counts() const {
  return m_impl->last_counts;
}

int RayTracer::cloth_geometry_creations() const {
  return m_impl->cloth_geometry.creations();
}

}  // namespace weft::render
