// Resource estimates for Slurm tasks (see slurm_resources.h; the model is docs/cluster.md's).

#include "app/cluster/slurm_resources.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/scene/scene.h"
#include "sim/simulator.h"

namespace weft::app {

namespace {

// The model's constants: the largest per-unit cost measured on one CPU of the development
// machine (docs/cluster.md, "Resource estimates", has the runs).
constexpr double kSecondsPerVertexStep = 8e-7;         // explicit integrators
constexpr double kSecondsPerVertexSolveStep = 1.2e-4;  // implicit Euler, fast projection
constexpr double kSecondsPerRasterPixel = 2.3e-6;      // per frame drawn, PNG written
constexpr double kSecondsPerRayPixelSample = 6e-6;     // per frame, pixel and sample
constexpr double kBaseMegabytes = 110.0;  // the program, its libraries, a GL context
constexpr double kMegabytesPerVertex = 4.2e-3;
constexpr double kMegabytesPerPixel = 1.1e-4;
// Margins over the estimate.
constexpr double kTimeMargin = 3.0;
constexpr int kStartMinutes = 5;
constexpr double kMemoryMargin = 2.0;

}  // namespace

TaskWork drawing_work(const Scene& scene, long frames) {
  TaskWork work;
  work.frames_drawn = frames;
  work.pixels = static_cast<long>(scene.render.width) * scene.render.height;
  if (scene.render.renderer == render::RendererKind::raytrace)
    work.samples = scene.render.raytrace.samples_per_pixel;
  return work;
}

TaskWork scene_work(const Scene& scene, bool draws) {
  TaskWork work = draws ? drawing_work(scene, scene.frames) : TaskWork{};
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  work.vertices = static_cast<long>(simulator->mesh().vertex_count());
  if (scene.dynamics) work.steps = simulator->substeps(1.0 / scene.fps) * scene.frames;
  // RK4 evaluates the forces four times a step.
  if (scene.sim.integrator == sim::Integrator::rk4) work.steps *= 4;
  work.solves = scene.sim.integrator == sim::Integrator::implicit_euler ||
                scene.sim.projection.method != sim::ProjectionMethod::none;
  return work;
}

double estimated_seconds(const TaskWork& w) {
  const double per_frame = w.samples > 0
                               ? kSecondsPerRayPixelSample * static_cast<double>(w.pixels) * w.samples
                               : kSecondsPerRasterPixel * static_cast<double>(w.pixels);
  return (w.solves ? kSecondsPerVertexSolveStep : kSecondsPerVertexStep) *
             static_cast<double>(w.vertices) * static_cast<double>(w.steps) +
         per_frame * static_cast<double>(w.frames_drawn);
}

double estimated_megabytes(const TaskWork& w) {
  return kBaseMegabytes + kMegabytesPerVertex * static_cast<double>(w.vertices) +
         (w.frames_drawn > 0 ? kMegabytesPerPixel * static_cast<double>(w.pixels) : 0.0);
}

SlurmResources estimate_resources(const std::vector<TaskWork>& works, int cpus) {
  double seconds = 0.0, megabytes = 0.0;
  for (const TaskWork& w : works) {
    seconds = std::max(seconds, estimated_seconds(w));
    megabytes = std::max(megabytes, estimated_megabytes(w));
  }
  SlurmResources r;
  r.cpus = std::max(1, cpus);
  r.time_minutes = kStartMinutes + static_cast<int>(std::ceil(kTimeMargin * seconds / 60.0));
  r.memory_mb = 64 * static_cast<long>(std::ceil(kMemoryMargin * megabytes / 64.0));
  char basis[200];
  std::snprintf(basis, sizeof basis,
                "estimated %.3g s and %.0f MB on one CPU for the largest task; asked %g× the "
                "time + %d min, %g× the memory (docs/cluster.md)",
                seconds, megabytes, kTimeMargin, kStartMinutes, kMemoryMargin);
  r.basis = basis;
  return r;
}

std::string slurm_time(int minutes) {
  if (minutes < 60) return std::to_string(minutes);
  char text[32];
  std::snprintf(text, sizeof text, "%d-%02d:%02d:00", minutes / (24 * 60), minutes / 60 % 24,
                minutes % 60);
  return text;
}

}  // namespace weft::app
