// The renderers' benchmark on the 64² sphere drape (a 30 cm sheet over a Ø10 cm sphere, as
// assets/scenes/sphere_drape_30.json, its drape built analytically: wrapped over the top of the
// sphere, hanging in eight folds below it) seen by that scene's camera:
// - the ray tracer at 640×480 with 1, 16 and 64 samples per pixel: seconds per frame and
//   Mrays/s per core, (a) "direct": camera and shadow rays only (ao_samples 0), (b) "default":
//   the default settings (one AO ray per sample as well);
// - the rasterizer (4× MSAA) at 1920×1080 through OSMesa and through EGL surfaceless: ms per
//   frame (each skipped with the reason when its context cannot be created).
// Each figure is the median over --repeats runs; threads: all hardware threads (--threads).
// Mrays per CPU second (process CPU time, all threads) is the per-core rate even when other
// work shares the cores; Mrays/s/core divides the wall-clock rate by the thread count.
//
// - with --only denoise, the ray tracer's denoiser: SSIM against a 1024-spp
//   reference and time of 4, 16 and 64 spp with and without it (denoise_sweep).
//
// Run: build/bench/raytrace_bench [--repeats 3] [--threads N] [--only raster|denoise] [--size WxH]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

#include "base/constants.h"
#include "base/thread_pool.h"
#include "base/timer.h"
#include "render/image_diff.h"
#include "render/primitives.h"
#include "render/raster.h"
#include "render/raytrace/ray_tracer.h"

namespace {

using namespace weft::render;
constexpr double sphere_radius_m = 0.05;
const Eigen::Vector3d sphere_center_m(0.0, 0.0, 0.25);

// The n×n sheet of side 0.3 m draped on the sphere: a flat-sheet point at distance s from the
// centre and angle φ lies on the sphere (2 mm off it) at polar angle s/R while s ≤ πR/2, then
// hangs a distance d = s − πR/2 below the equator, flaring out, with folds of angular
// frequency 8 growing over its first 5 cm.
RenderMesh sphere_drape(int n) {
  const double r = sphere_radius_m + 0.002;
  return make_grid_mesh(n, n, [r](double u, double v) {
    const double x = 0.3 * (u - 0.5), y = 0.3 * (v - 0.5);
    const double s = std::hypot(x, y), phi = std::atan2(y, x);
    if (s <= 0.5 * weft::base::kPi * r) {
      const double theta = s / r;
      return Eigen::Vector3d(sphere_center_m + r * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                                   std::sin(theta) * std::sin(phi),
                                                                   std::cos(theta)));
    }
    const double d = s - 0.5 * weft::base::kPi * r;
    const double fold = 0.6 * std::min(d / 0.05, 1.0) * std::sin(8.0 * phi);
    const double rho = r + 0.35 * d * (1.0 + fold);
    const double angle = phi + 0.04 * fold;
    return Eigen::Vector3d(
        sphere_center_m + Eigen::Vector3d(rho * std::cos(angle), rho * std::sin(angle), -0.93 * d));
  });
}

// sphere_drape_30.json's render block.
RenderSettings scene_settings(int width, int height) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.camera.eye = {0.45, -0.55, 0.55};
  s.camera.target = {0, 0, 0.2};
  s.camera.fov_y_deg = 35;
  s.light_direction = {1.0, -0.5, 0.8};
  s.light_intensity = 0.85;
  s.ambient = 0.2;
  s.ground_half_size_m = 1.0;
  s.raytrace.adaptive_error = 0.0;  // uniform: every pixel takes the samples asked for
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

template <class F>
double seconds(F&& f) {
  const weft::base::Stopwatch watch;
  f();
  return watch.seconds();
}

// --only denoise: the denoiser's table (docs/benchmarks.md). The sphere drape at --size (default
// 400x300) with the default ray tracer settings (soft shadows, one AO ray per sample) at 1024
// samples per pixel, plain, is the reference; each row is one render against it: samples, denoiser,
// SSIM and PSNR against the reference (weft diff's measures, render/image_diff.h), seconds (median
// of --repeats).
void denoise_sweep(const RenderMesh& cloth, const std::vector<RenderObject>& sphere, int width,
                   int height, int threads, int repeats) {
  RayTracer tracer;
  RenderSettings s = scene_settings(width, height);
  s.raytrace.threads = threads;
  const auto render = [&](int spp, bool denoise, double& median_s) {
    s.raytrace.samples_per_pixel = spp;
    s.raytrace.denoise = denoise;
    Image image;
    std::vector<double> times;
    for (int k = 0; k < repeats; ++k) times.push_back(seconds([&] { image = tracer.render(cloth, s, sphere); }));
    median_s = median(times);
    return image;
  };
  double reference_s = 0.0;
  tracer.render(cloth, s, sphere);  // warm-up: builds the BVHs
  const int saved_repeats = repeats;
  repeats = 1;
  const Image reference = render(1024, false, reference_s);
  repeats = saved_repeats;
  std::printf("\ndenoiser, sphere drape %dx%d, %d threads; reference: 1024 spp plain (%.1f s)\n",
              width, height, threads, reference_s);
  std::printf("%5s %8s %8s %9s %9s\n", "spp", "denoise", "SSIM", "PSNR dB", "s/frame");
  for (const auto& [spp, denoise] : std::vector<std::pair<int, bool>>{
           {4, false}, {4, true}, {16, false}, {16, true}, {64, false}, {64, true}}) {
    double t = 0.0;
    const ImageDifference d = compare_images(reference, render(spp, denoise, t));
    std::printf("%5d %8s %8.4f %9.2f %9.3f\n", spp, denoise ? "on" : "off", d.ssim, d.psnr_db, t);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 3;
  bool raster_only = false;  // --only raster: skip the ray tracer
  bool denoise_only = false;  // --only denoise: the denoiser's table alone
  int width = 400, height = 300;  // --size, of the denoiser's table
  int threads = static_cast<int>(weft::base::hardware_threads());
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--repeats"))
      repeats = std::max(1, std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--threads"))
      threads = std::max(1, std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--only") && !std::strcmp(argv[i + 1], "raster"))
      raster_only = true;
    else if (!std::strcmp(argv[i], "--only") && !std::strcmp(argv[i + 1], "denoise"))
      denoise_only = true;
    else if (!std::strcmp(argv[i], "--size") && std::sscanf(argv[i + 1], "%dx%d", &width, &height) == 2)
      continue;
    else {
      std::fprintf(stderr,
                   "usage: raytrace_bench [--repeats N] [--threads N] [--only raster|denoise] "
                   "[--size WxH]\n");
      return 1;
    }
  }
  const RenderMesh cloth = sphere_drape(64);
  const std::vector<RenderObject> sphere{
      {make_sphere_mesh(sphere_center_m, sphere_radius_m), {0.70f, 0.74f, 0.80f}}};
  std::printf("sphere drape: %zu cloth triangles, %zu sphere triangles; %d threads, median of %d\n",
              cloth.triangles.size(), sphere[0].mesh.triangles.size(), threads, repeats);

  if (denoise_only) {
    denoise_sweep(cloth, sphere, width, height, threads, repeats);
    return 0;
  }
  if (!raster_only) {
    RayTracer tracer;
    std::printf("\n%s, 640x480\n", tracer.description().c_str());
    std::printf("%-8s %4s %8s %9s %13s %14s %8s %8s %8s\n", "config", "spp", "s/frame", "Mrays/s",
                "Mrays/s/core", "Mrays/cpu-s", "camera", "shadow", "AO");
    for (const char* config : {"direct", "default"}) {
      for (int spp : {1, 16, 64}) {
        RenderSettings s = scene_settings(640, 480);
        s.raytrace.samples_per_pixel = spp;
        s.raytrace.threads = threads;
        if (!std::strcmp(config, "direct")) s.raytrace.ao_samples = 0;
        tracer.render(cloth, s, sphere);  // warm-up: builds the BVHs
        std::vector<double> times, cpu_times;
        for (int k = 0; k < repeats; ++k) {
          const std::clock_t cpu_start = std::clock();
          times.push_back(seconds([&] { tracer.render(cloth, s, sphere); }));
          cpu_times.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        }
        const RayCounts rays = tracer.last_ray_counts();
        const double t = median(times);
        const auto millions = [](std::uint64_t n) { return static_cast<double>(n) / 1e6; };
        const double mrays = millions(rays.total()) / t;
        std::printf("%-8s %4d %8.3f %9.1f %13.1f %14.1f %7.2fM %7.2fM %7.2fM\n", config, spp, t,
                    mrays, mrays / threads, millions(rays.total()) / median(cpu_times),
                    millions(rays.camera), millions(rays.shadow), millions(rays.occlusion));
      }
    }
  }

  std::printf("\nrasterizer, 1920x1080, 4x MSAA\n");
  for (GlBackend backend : {GlBackend::osmesa, GlBackend::egl}) {
    try {
      RasterRenderer raster(backend == GlBackend::egl ? make_egl_context(1920, 1080)
                                                      : make_osmesa_context(1920, 1080));
      const RenderSettings s = scene_settings(1920, 1080);
      raster.render(cloth, s, sphere);  // warm-up: allocates the targets
      std::vector<double> times;
      for (int k = 0; k < std::max(repeats, 5); ++k)
        times.push_back(seconds([&] { raster.render(cloth, s, sphere); }));
      std::printf("%s: %.1f ms per frame\n", raster.description().c_str(), 1e3 * median(times));
    } catch (const std::exception& e) {
      std::printf("%s skipped: %s\n", gl_backend_name(backend), e.what());
    }
  }
  return 0;
}
