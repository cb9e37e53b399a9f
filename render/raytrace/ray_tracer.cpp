// Embree ray tracer. Per render():
//   1. validate the settings (RenderSettings and its raytrace part) and the meshes, computing
//      vertex normals on a copy where missing,
//   2. bring the Embree scene up to date: the cloth's geometry is kept while its triangles
//      stay the same (only the vertex buffer is rewritten), objects likewise, the ground is a
//      square under the camera target as the rasterizer's; commit (BVH build, one thread),
//   3. a FrameView of the camera, lights and surfaces (integrator.h),
//   4. threads take 16×16 tiles off a shared counter and write their pixels' bytes; a pixel's
//      value depends on its own samples only, so the image is the same for any thread count.

#include "render/raytrace/ray_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "render/primitives.h"
#include "render/raytrace/embree_scene.h"
#include "render/raytrace/integrator.h"
#include "render/raytrace/shading.h"

namespace weft::render {

namespace {

constexpr int max_image_side = 16384;
constexpr int tile_side = 16;
constexpr double pi = 3.14159265358979323846;

void validate_raytrace(const RayTraceSettings& r) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RenderSettings: raytrace." + what);
  };
  if (r.samples_per_pixel < 1 || r.samples_per_pixel > 65536)
    fail("samples_per_pixel must be in 1..65536, got " + std::to_string(r.samples_per_pixel));
  if (r.bounces < 0 || r.bounces > 64)
    fail("bounces must be in 0..64, got " + std::to_string(r.bounces));
  if (r.ao_samples < 0 || r.ao_samples > 1024)
    fail("ao_samples must be in 0..1024, got " + std::to_string(r.ao_samples));
  if (!(r.ao_distance_m > 0.0) || !std::isfinite(r.ao_distance_m))
    fail("ao_distance_m must be finite and > 0");
  if (!(r.sun_angular_radius_deg >= 0.0 && r.sun_angular_radius_deg <= 45.0))
    fail("sun_angular_radius_deg must be in [0, 45]");
  if (!(r.sheen >= 0.0 && r.sheen <= 1.0)) fail("sheen must be in [0, 1]");
  if (!(r.sheen_roughness > 0.0 && r.sheen_roughness <= 1.0))
    fail("sheen_roughness must be in (0, 1]");
  if (r.threads < 0 || r.threads > 4096)
    fail("threads must be in 0..4096 (0: all hardware threads), got " + std::to_string(r.threads));
}

int thread_count(const RayTraceSettings& r, int tiles) {
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::clamp(r.threads > 0 ? r.threads : hardware, 1, std::max(tiles, 1));
}

float max_abs_coordinate(const RenderMesh& mesh) {
  float m = 0.0f;
  for (const Eigen::Vector3f& p : mesh.positions) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

}  // namespace

struct RayTracer::Impl {
  rt::EmbreeDevice device;  // declared first: released last
  rt::EmbreeScene scene{device};
  rt::TriangleGeometry cloth_geometry, ground_geometry;
  std::vector<std::unique_ptr<rt::TriangleGeometry>> object_geometries;
  RayCounts last_counts;

  Image render(const RenderMesh& cloth, const RenderSettings& s,
               const std::vector<RenderObject>& objects);
};

Image RayTracer::Impl::render(const RenderMesh& cloth_input, const RenderSettings& s,
                              const std::vector<RenderObject>& objects) {
  validate(s, max_image_side);
  validate_raytrace(s.raytrace);
  validate(s.cloth_surface);
  validate(cloth_input);
  RenderMesh cloth_storage;
  const RenderMesh& cloth = with_normals(cloth_input, cloth_storage);
  std::vector<RenderMesh> object_storage(objects.size());
  std::vector<const RenderMesh*> object_meshes;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const std::string name = "object " + std::to_string(k);
    validate(objects[k].mesh, name);
    if (!objects[k].color.allFinite()) throw std::invalid_argument(name + ": colour is not finite");
    object_meshes.push_back(&with_normals(objects[k].mesh, object_storage[k]));
  }
  RenderMesh ground;
  if (s.ground) {
    ground =
        make_square_patch(Eigen::Vector3d(s.camera.target.x(), s.camera.target.y(), s.ground_z_m),
                          Eigen::Vector3d::UnitZ(), s.ground_half_size_m);
  }

  // 2. The Embree scene.
  cloth_geometry.set(device, scene, cloth.positions, cloth.triangles);
  ground_geometry.set(device, scene, ground.positions, ground.triangles);
  while (object_geometries.size() < objects.size())
    object_geometries.push_back(std::make_unique<rt::TriangleGeometry>());
  object_geometries.resize(objects.size());  // released ones detach themselves
  for (std::size_t k = 0; k < objects.size(); ++k)
    object_geometries[k]->set(device, scene, object_meshes[k]->positions,
                              object_meshes[k]->triangles);
  scene.commit(device);

  // 3. What the pixels read.
  rt::FrameView view;
  view.scene = scene.get();
  const auto add_surface = [&](const rt::TriangleGeometry& g, rt::SurfaceShading surface) {
    if (!g.attached()) return;
    if (view.surfaces.size() <= g.id()) view.surfaces.resize(g.id() + 1);
    view.surfaces[g.id()] = surface;
  };
  float extent = std::max(max_abs_coordinate(cloth), max_abs_coordinate(ground));
  add_surface(cloth_geometry,
              {&cloth, rt::reflectance_from_color(s.front_color),
               rt::reflectance_from_color(s.back_color), true, false,
               s.cloth_surface.texture.image ? &s.cloth_surface.texture : nullptr});
  const Eigen::Vector3f ground_reflectance = rt::reflectance_from_color(s.ground_color);
  add_surface(ground_geometry, {&ground, ground_reflectance, ground_reflectance, false, true});
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const Eigen::Vector3f reflectance = rt::reflectance_from_color(objects[k].color);
    add_surface(*object_geometries[k], {object_meshes[k], reflectance, reflectance, false, false});
    extent = std::max(extent, max_abs_coordinate(*object_meshes[k]));
  }

  view.width = s.width;
  view.height = s.height;
  // The camera basis of Camera::view_matrix (which also checks eye, target and up).
  const Eigen::Matrix4f view_matrix = s.camera.view_matrix();
  const double aspect = static_cast<double>(s.width) / static_cast<double>(s.height);
  const Eigen::Matrix4f projection = s.camera.projection_matrix(aspect);  // checks fov, near, far
  const Eigen::Vector3f side = view_matrix.block<1, 3>(0, 0).transpose();
  const Eigen::Vector3f true_up = view_matrix.block<1, 3>(1, 0).transpose();
  view.forward = -view_matrix.block<1, 3>(2, 0).transpose();
  // At depth 1 the image spans ±1/P(0,0) sideways and ±1/P(1,1) up and down.
  view.right = side / projection(0, 0);
  view.up = true_up / projection(1, 1);
  view.eye = s.camera.eye.cast<float>();
  view.near_m = static_cast<float>(s.camera.near_m);
  view.far_m = static_cast<float>(s.camera.far_m);
  view.pixel_angle = 2.0f / (projection(1, 1) * static_cast<float>(s.height));
  extent = std::max(extent, view.eye.cwiseAbs().maxCoeff());

  view.shading = s.shading;
  view.sun = s.light_direction.normalized().cast<float>();
  view.sun_cos_max = static_cast<float>(std::cos(s.raytrace.sun_angular_radius_deg * pi / 180.0));
  view.sun_intensity = static_cast<float>(s.light_intensity);
  view.sky = static_cast<float>(s.ambient);
  view.background = rt::reflectance_from_color(s.background);
  view.ground = s.ground;
  view.ground_center =
      Eigen::Vector3d(s.camera.target.x(), s.camera.target.y(), s.ground_z_m).cast<float>();
  view.ground_half_size_m = static_cast<float>(s.ground_half_size_m);
  view.samples_per_pixel = s.raytrace.samples_per_pixel;
  view.bounces = s.raytrace.bounces;
  view.ao_samples = s.raytrace.ao_samples;
  view.ao_distance_m = static_cast<float>(s.raytrace.ao_distance_m);
  view.sheen = static_cast<float>(s.raytrace.sheen);
  view.sheen_roughness = static_cast<float>(s.raytrace.sheen_roughness);
  view.seed = s.raytrace.seed;
  // Float positions near `extent` are exact to ~6e-8 extent; Embree's hits to a few ulps more.
  view.epsilon_m = 2e-5f * (1.0f + extent);

  // 4. Tiles over threads.
  Image image(s.width, s.height);
  const int tiles_x = (s.width + tile_side - 1) / tile_side;
  const int tiles_y = (s.height + tile_side - 1) / tile_side;
  const int tiles = tiles_x * tiles_y;
  const int threads = thread_count(s.raytrace, tiles);
  std::atomic<int> next_tile{0};
  std::vector<RayCounts> counts(static_cast<std::size_t>(threads));
  std::exception_ptr failure;
  std::mutex failure_mutex;
  std::uint8_t* const bytes = image.data();
  const auto work = [&](int worker) {
    try {
      RayCounts& mine = counts[static_cast<std::size_t>(worker)];
      for (int tile = next_tile++; tile < tiles; tile = next_tile++) {
        const int x0 = (tile % tiles_x) * tile_side, y0 = (tile / tiles_x) * tile_side;
        const int x1 = std::min(x0 + tile_side, s.width), y1 = std::min(y0 + tile_side, s.height);
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            const Eigen::Vector3f radiance = rt::render_pixel(view, x, y, mine);
            std::uint8_t* out = bytes + 3 * (static_cast<std::size_t>(y) * s.width + x);
            for (int c = 0; c < 3; ++c) out[c] = rt::encode_channel(radiance[c]);
          }
        }
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next_tile = tiles;  // the others stop after their tile
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(work, t);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the tiles are shared among those running
    }
  }
  work(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);

  last_counts = {};
  for (const RayCounts& c : counts) {
    last_counts.camera += c.camera;
    last_counts.shadow += c.shadow;
    last_counts.occlusion += c.occlusion;
    last_counts.bounce += c.bounce;
  }
  return image;
}

RayTracer::RayTracer() : m_impl(std::make_unique<Impl>()) {}
RayTracer::~RayTracer() = default;

Image RayTracer::render(const RenderMesh& cloth, const RenderSettings& settings,
                        const std::vector<RenderObject>& objects) {
  return m_impl->render(cloth, settings, objects);
}

std::string RayTracer::description() const {
  return "Embree " + std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) +
         "." + std::to_string(RTC_VERSION_PATCH) + " ray tracer";
}

RayCounts RayTracer::last_ray_counts() const {
  return m_impl->last_counts;
}

int RayTracer::cloth_geometry_creations() const {
  return m_impl->cloth_geometry.creations();
}

}  // namespace weft::render
