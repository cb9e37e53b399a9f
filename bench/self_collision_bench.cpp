// The self-collision benchmark: a 64² cloth (1 m, Kang & Yu wool, symplectic Euler)
// dropped from 20 cm onto a Ø50 cm sphere resting on the ground, with and without
// self-collision. Runs are interleaved (off, on, off, on, …) so that a busy machine slows both
// alike. The table gives the medians over repeats of the wall time and of the process's CPU
// time per frame (24 fps; CPU time is less disturbed by other work on the machine, and counts
// every thread: self-collision builds its candidate list on --threads threads, 0 for all
// hardware threads, while the rest of the step runs on one), the step count, implicit Euler's
// conjugate-gradient iterations per step (0 with symplectic Euler), the self-contacts per step,
// the candidate pairs in the list, the broad- and narrow-phase shares of the frame time, the
// rebuilds of the proximity candidates, the pairs the impact zones test by continuous collision
// per step (sim/collision/impact_zones.h), the most edge–triangle crossings in a frame (counted
// outside the timed steps), the steps a projection left above its tolerance and the largest
// strain it left; then the on/off ratios of the medians.
//
// --inextensible: the same drop with fast projection (tol 1e-3) after implicit Euler solved by
// conjugate gradients to 1e-3 (h = 1/120 s), the inextensible model bench/inextensibility_sweep
// times.
//
// --failsafe-interval S: SelfCollisionSettings::failsafe_interval_s (0: the failsafe every step).
// --block-jacobi: conjugate gradients preconditioned by block Jacobi instead of "auto" (block
// Jacobi and the lines for its slow solves on this grid).
//
// Run: build/bench/self_collision_bench [--n 64] [--seconds 1.5] [--repeats 3] [--threads 0]
//                                       [--inextensible] [--failsafe-interval 0.001] [--block-jacobi]

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "sim/collision/self_intersection.h"
#include "sim/simulator.h"

namespace {

using namespace weft::sim;

struct Run {
  double ms_per_frame = 0.0;
  double cpu_ms_per_frame = 0.0;  // all threads' CPU time: less disturbed by a busy machine
  long steps = 0;
  double contacts_per_step = 0.0;  // max over each frame's steps, averaged over frames
  double broad_share = 0.0, narrow_share = 0.0;
  long rebuilds = 0;
  double zone_pairs_per_step = 0.0;  // pairs the impact zones tested by continuous collision
  double candidates = 0.0;  // candidate pairs in the list, averaged over frames
  Index crossings = 0;      // edge–triangle crossings, the most in a frame (not timed)
  long unconverged_steps = 0;  // steps the projection left above its tolerance
  long cg_iterations = 0;      // implicit Euler's conjugate gradients, over the run
  double worst_strain = 0.0;   // the largest strain a projection left
};

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// How each drop is stepped, besides whether it collides with itself.
struct DropSettings {
  Index n = 64;
  double seconds = 1.5;
  int threads = 0;
  bool inextensible = false;
  double failsafe_interval_s = SelfCollisionSettings{}.failsafe_interval_s;
  CgPreconditioner preconditioner = CgPreconditioner::automatic;
};

Run drop_on_sphere(const DropSettings& drop, bool self_collision) {
  const Index n = drop.n;
  const double seconds = drop.seconds;
  const int threads = drop.threads;
  GridSpec grid;
  grid.nu = grid.nv = n;
  grid.origin = Vec3(-0.5, -0.5, 0.72);
  SimSettings settings;
  settings.obstacles = {SphereObstacle{Vec3(0.0, 0.0, 0.25), 0.25},
                        PlaneObstacle{Vec3::Zero(), Vec3::UnitZ()}};
  settings.collision_friction = 0.3;
  settings.self_collision.enabled = self_collision;
  settings.self_collision.thickness_m = 3e-3;
  settings.self_collision.threads = threads;
  settings.self_collision.failsafe_interval_s = drop.failsafe_interval_s;
  settings.solver_threads = threads;
  if (drop.inextensible) {
    settings.integrator = Integrator::implicit_euler;
    settings.implicit_solve = ImplicitSolve::conjugate_gradient;
    settings.implicit_cg_tolerance = 1e-3;
    settings.implicit_cg_preconditioner = drop.preconditioner;
    settings.projection.method = ProjectionMethod::fast_projection;
  }
  Material wool;  // the defaults: Kang & Yu wool (seed 002)
  Simulator sim(make_grid(grid), wool, {}, settings);
  const double fps = 24.0;
  const int frames = static_cast<int>(seconds * fps + 0.5);
  Run r;
  double contact_sum = 0.0;
  const auto triangles = sim.mesh().triangles();
  const auto edges = unique_edges(triangles);
  double total_s = 0.0, cpu_s = 0.0;
  for (int f = 0; f < frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start_s = process_cpu_s();
    sim.advance(1.0 / fps);
    total_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu_s += process_cpu_s() - cpu_start_s;
    const StepStatistics s = sim.take_step_statistics();
    r.steps += s.steps;
    r.unconverged_steps += s.unconverged_steps;
    r.cg_iterations += s.cg_iterations;
    r.worst_strain = std::max(r.worst_strain, s.worst_projected_strain);
    contact_sum += static_cast<double>(s.max_self_contacts);
    if (const SelfCollision* self = sim.self_collision())
      r.candidates += static_cast<double>(self->candidate_count()) / frames;
    r.crossings = std::max(r.crossings, count_edge_triangle_crossings(sim.state().x, triangles, edges));
  }
  r.ms_per_frame = 1e3 * total_s / frames;
  r.cpu_ms_per_frame = 1e3 * cpu_s / frames;
  r.contacts_per_step = contact_sum / frames;
  if (const SelfCollision* self = sim.self_collision()) {
    r.broad_share = self->broad_phase_s() / total_s;
    r.narrow_share = self->narrow_phase_s() / total_s;
    r.rebuilds = self->rebuilds();
  }
  if (const ImpactZones* zones = sim.impact_zones())
    r.zone_pairs_per_step = static_cast<double>(zones->tested_pairs()) / static_cast<double>(r.steps);
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace

int main(int argc, char** argv) {
  DropSettings drop;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--inextensible")) drop.inextensible = true;
    else if (!std::strcmp(argv[i], "--block-jacobi")) drop.preconditioner = CgPreconditioner::block_jacobi;
    else if (!std::strcmp(argv[i], "--n") && has_value) drop.n = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--seconds") && has_value) drop.seconds = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--repeats") && has_value) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && has_value) drop.threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--failsafe-interval") && has_value)
      drop.failsafe_interval_s = std::atof(argv[++i]);
    else {
      std::fprintf(stderr,
                   "usage: %s [--n 64] [--seconds 1.5] [--repeats 3] [--threads 0] [--inextensible] "
                   "[--failsafe-interval 0.001] [--block-jacobi]\n",
                   argv[0]);
      return 1;
    }
  }
  if (drop.n < 2 || drop.seconds <= 0.0 || repeats < 1 || drop.threads < 0 ||
      !(drop.failsafe_interval_s >= 0.0)) {
    std::fprintf(stderr, "self_collision_bench: need --n >= 2, --seconds > 0, --repeats >= 1, "
                         "--threads >= 0, --failsafe-interval >= 0 (seconds)\n");
    return 1;
  }
  std::vector<Run> off, on;
  for (int k = 0; k < repeats; ++k) {
    off.push_back(drop_on_sphere(drop, false));
    on.push_back(drop_on_sphere(drop, true));
  }
  std::printf("%d^2 cloth dropped on a sphere (%s), %.2f s simulated, %d interleaved repeats "
              "(medians), candidate list on %s\n",
              static_cast<int>(drop.n),
              drop.inextensible ? "fast projection after implicit Euler" : "mass-spring, symplectic Euler",
              drop.seconds, repeats,
              drop.threads == 0 ? "all hardware threads"
                                : (std::to_string(drop.threads) + " thread(s)").c_str());
  std::printf("%-15s %9s %13s %8s %8s %14s %11s %7s %7s %9s %11s %10s %10s %8s\n", "self-collision",
              "ms/frame", "cpu ms/frame", "steps", "CG/step", "contacts/step", "candidates", "broad",
              "narrow", "rebuilds", "CCD/step", "crossings", "above tol", "strain");
  const auto row = [](const char* name, const std::vector<Run>& runs) {
    std::vector<double> ms, cpu_ms, broad, narrow, contacts, candidates;
    for (const Run& r : runs) {
      ms.push_back(r.ms_per_frame);
      cpu_ms.push_back(r.cpu_ms_per_frame);
      candidates.push_back(r.candidates);
      broad.push_back(r.broad_share);
      narrow.push_back(r.narrow_share);
      contacts.push_back(r.contacts_per_step);
    }
    std::printf("%-15s %9.1f %13.1f %8ld %8.1f %14.0f %11.0f %6.1f%% %6.1f%% %9ld %11.0f %10d %10ld %7.3f%%\n",
                name, median(ms), median(cpu_ms), runs.front().steps,
                static_cast<double>(runs.front().cg_iterations) / static_cast<double>(runs.front().steps),
                median(contacts),
                median(candidates), 100.0 * median(broad), 100.0 * median(narrow),
                runs.front().rebuilds, runs.front().zone_pairs_per_step, runs.back().crossings,
                runs.back().unconverged_steps, 100.0 * runs.back().worst_strain);
    return std::array<double, 2>{median(ms), median(cpu_ms)};
  };
  const auto ms_off = row("off", off);
  const auto ms_on = row("on", on);
  std::printf("self-collision adds %.0f %% to the frame time (ratio of medians %.3f; of CPU time "
              "%.3f, +%.0f %%)\n",
              100.0 * (ms_on[0] / ms_off[0] - 1.0), ms_on[0] / ms_off[0], ms_on[1] / ms_off[1],
              100.0 * (ms_on[1] / ms_off[1] - 1.0));
  return 0;
}
