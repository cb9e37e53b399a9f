// The speed/accuracy trade of inextensibility, measured: a 1 m × 1 m
// wool sheet hanging from two adjacent corners, 48 frames at 24 fps, simulated by
//   - fast projection (Goldenthal 2007) at tolerances 1e-2, 1e-3, 1e-4,
//   - pairwise projection (Provot / PBD Gauss–Seidel) with N sweeps per step,
//   - stiff warp/weft springs with implicit Euler,
// each after the same unconstrained implicit-Euler step (--cg: solved by conjugate gradients
// under a projection; stiff springs always by the direct solver). Prints one row per run:
// wall time per frame (median of the frames), projection and CG iterations per step, and the
// largest and mean warp/weft strain over the frames after the first 0.5 s (the sheet starts
// flat: a singular start), and the steps whose projection missed its tolerance.
//
//   build/bench/inextensibility_sweep [--sizes 32,64,128] [--step 0.0083333] [--backend NAME]
//                                     [--cg TOLERANCE] [--quick] [--methods SUBSTRING]
//                                     [--reuse N] [--threads N] [--frames N] [--no-hold]
//                                     [--adaptive STRAIN] [--max-step SECONDS]
//                                     [--block-jacobi | --lines | --multigrid] [--bending auto|explicit|implicit]
// --reuse: fast projection's CG iterations on a reused factorization (0: a factorization per
// iteration, the paper's); --threads: implicit Euler's CG threads (0: all); --frames: fewer
// frames for the largest sizes (the rows then cover only that start); --no-hold: project the
// top edge between the pins instead of holding it (sim/constraints/taut_chains.h), to measure
// what holding it buys; --adaptive: fast projection with the adaptive step
// (sim/adaptive_step.h) aiming its prediction's strain at STRAIN, its steps at most --max-step
// (default 1/24 s; --step is then unused); --block-jacobi, --lines, --multigrid: CG's preconditioner
// (default: "auto", the multigrid from 150² vertices, the lines below); --bending: simulation.bending_in_step
// (default "auto": in implicit Euler's matrix when explicit bending would be unstable at a
// fixed step, docs/models.md). After the rows, the speed
// targets for fast projection at tol 1e-2, with the growth exponent.
#include <algorithm>
#include <cmath>
#include <utility>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "sim/pins.h"
#include "sim/simulator.h"

namespace {

using namespace weft::sim;

struct Method {
  std::string name;
  ProjectionMethod projection = ProjectionMethod::none;
  double tolerance = 1e-3;
  int iterations = 30;
  double stretch_scale = 1.0;  // stiff springs: multiple of the wool's tensile rigidity
};

struct Row {
  double ms_per_frame = 0.0;   // median over frames
  double cpu_ms_per_frame = 0.0;  // process CPU time, mean over frames (robust to a busy machine)
  double factorizations_per_step = 0.0;
  double iterations_per_step = 0.0, cg_per_step = 0.0;
  int max_iterations = 0;
  double max_strain = 0.0, mean_strain = 0.0;
  double max_strain_every_frame = 0.0;  // over every frame, the first 0.5 s included
  long unconverged = 0;
  double steps_per_frame = 0.0;
  long rejected = 0;  // adaptive steps redone shorter
  bool diverged = false;
};

struct Options {
  double step_s = 1.0 / 120.0;
  SparseBackend backend = default_sparse_backend();
  double cg_tolerance = 0.0;  // > 0: implicit Euler by conjugate gradients to this residual
  int reuse_iterations = ProjectionSettings{}.reuse_iterations;
  int threads = 0;  // conjugate gradients' matrix–vector product
  int frames = 48;
  bool hold_taut_chains = true;
  double adaptive_strain = 0.0;  // > 0: the adaptive step, aiming at this prediction strain
  double max_step_s = 1.0 / 24.0;
  CgPreconditioner preconditioner = CgPreconditioner::automatic;
  BendingInStep bending = BendingInStep::automatic;
};

Row run(Index n, const Method& method, const Options& options) {
  GridSpec grid;
  grid.nu = grid.nv = n;
  grid.origin = Vec3(-0.5, 0.0, 1.6);
  const ClothMesh mesh = make_grid(grid);
  Material wool;  // Kang & Yu, seed 002
  wool.stretch_warp_N_m *= method.stretch_scale;
  wool.stretch_weft_N_m *= method.stretch_scale;
  SimSettings s;
  s.integrator = Integrator::implicit_euler;
  s.time_step = fixed_time_step(options.step_s);
  s.air_damping_1_s = 1.0;
  s.sparse_backend = options.backend;
  // CG for the soft system under a projection; stiff springs make CG crawl (it reached 13 %
  // strain in its 200 iterations at ×100), so they keep the direct solve.
  if (options.cg_tolerance > 0.0 && method.projection != ProjectionMethod::none) {
    s.implicit_solve = ImplicitSolve::conjugate_gradient;
    s.implicit_cg_tolerance = options.cg_tolerance;
    s.implicit_cg_preconditioner = options.preconditioner;
  }
  s.bending_in_step = options.bending;
  s.projection.method = method.projection;
  s.projection.tolerance = method.tolerance;
  s.projection.max_iterations = method.iterations;
  s.projection.reuse_iterations = options.reuse_iterations;
  s.projection.hold_taut_chains = options.hold_taut_chains;
  s.solver_threads = options.threads;
  if (options.adaptive_strain > 0.0 && method.projection == ProjectionMethod::fast_projection) {
    s.time_step = adaptive_time_step();
    s.time_step.adaptive.max_prediction_strain = options.adaptive_strain;
    s.time_step.adaptive.max_step_s = options.max_step_s;
  }
  Simulator sim(mesh, wool, resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), s);

  Row row;
  std::vector<double> frame_ms;
  long steps = 0, iterations = 0, cg_iterations = 0, factorizations = 0;
  const std::clock_t cpu_start = std::clock();
  double strain_sum = 0.0;
  int strain_frames = 0;
  for (int frame = 1; frame <= options.frames; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    try {
      sim.advance(frame / 24.0 - sim.state().time_s);
    } catch (const DivergenceError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      row.diverged = true;
      return row;
    }
    frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    const StepStatistics st = sim.take_step_statistics();
    steps += st.steps;
    iterations += st.projection_iterations;
    factorizations += st.projection_factorizations;
    cg_iterations += st.cg_iterations;
    row.max_iterations = std::max(row.max_iterations, st.max_projection_iterations);
    row.unconverged += st.unconverged_steps;
    row.rejected += st.rejected_steps;
    const Diagnostics d = sim.diagnostics();
    row.max_strain_every_frame = std::max(row.max_strain_every_frame, d.max_strain);
    if (frame / 24.0 > 0.5) {
      row.max_strain = std::max(row.max_strain, d.max_strain);
      strain_sum += d.mean_strain;
      ++strain_frames;
    }
  }
  std::nth_element(frame_ms.begin(), frame_ms.begin() + frame_ms.size() / 2, frame_ms.end());
  row.ms_per_frame = frame_ms[frame_ms.size() / 2];
  row.cpu_ms_per_frame = 1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / options.frames;
  row.iterations_per_step = static_cast<double>(iterations) / static_cast<double>(steps);
  row.factorizations_per_step = static_cast<double>(factorizations) / static_cast<double>(steps);
  row.cg_per_step = static_cast<double>(cg_iterations) / static_cast<double>(steps);
  row.steps_per_frame = static_cast<double>(steps) / options.frames;
  row.mean_strain = strain_frames > 0 ? strain_sum / strain_frames : 0.0;
  return row;
}

std::vector<int> parse_list(const char* text) {
  std::vector<int> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atoi(item.c_str()));
  return out;
}

// The speed targets for fast projection at tol 1e-2 (max strain ≤ 1 %, every step converged),
// CPU time per frame over the whole run (the median frame's wall time hides a frame with a
// crawling projection), and the growth exponent of the time with the vertex count between the
// smallest and the largest size run. The targets: 0.1, 0.12 and 0.15 times Blender's cloth
// at 64², 128² and 256² (bench/cloth_vs_blender.py).
void print_targets(const std::vector<std::pair<int, Row>>& rows) {
  if (rows.empty()) return;
  const auto target_ms = [](int n) { return n == 64 ? 17.0 : n == 128 ? 80.0 : n == 256 ? 500.0 : 0.0; };
  std::printf("\ntargets, fast projection tol 1e-2 (CPU ms per frame over the run, against the "
              "target; the median frame's wall ms beside it):\n");
  std::printf("%-6s %10s %8s %8s %11s %7s %s\n", "size", "median ms", "cpu ms", "target",
              "max strain", "unconv", "met");  // strain: every frame
  for (const auto& [n, r] : rows) {
    const double target = target_ms(n);
    const bool met = target > 0.0 && r.cpu_ms_per_frame <= target && r.max_strain_every_frame <= 0.01 &&
                     r.unconverged == 0;
    std::printf("%-6s %10.1f %8.1f %8.0f %10.4f%% %7ld %s\n", (std::to_string(n) + "²").c_str(),
                r.ms_per_frame, r.cpu_ms_per_frame, target, 100 * r.max_strain_every_frame, r.unconverged,
                target > 0.0 ? (met ? "yes" : "no") : "-");
  }
  if (rows.size() >= 2 && rows.front().first != rows.back().first) {
    const double vertices = std::log(double(rows.back().first) * rows.back().first /
                                     (double(rows.front().first) * rows.front().first));
    std::printf("time grows as vertices^%.2f (wall), ^%.2f (cpu) from %d² to %d² (target: at most 1.3)\n",
                std::log(rows.back().second.ms_per_frame / rows.front().second.ms_per_frame) / vertices,
                std::log(rows.back().second.cpu_ms_per_frame / rows.front().second.cpu_ms_per_frame) / vertices,
                rows.front().first, rows.back().first);
  }
}

// The command line into sizes, options, --quick and --methods; false (after a message) when it
// is not understood.
bool parse_arguments(int argc, char** argv, std::vector<int>* sizes, Options* options,
                     bool* quick, std::string* only) {
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) *sizes = parse_list(argv[++i]);
    else if (!std::strcmp(argv[i], "--step") && i + 1 < argc) options->step_s = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--backend") && i + 1 < argc) options->backend = sparse_backend_from_name(argv[++i]);
    else if (!std::strcmp(argv[i], "--cg") && i + 1 < argc) options->cg_tolerance = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--reuse") && i + 1 < argc) options->reuse_iterations = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) options->threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) options->frames = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--quick")) *quick = true;
    else if (!std::strcmp(argv[i], "--no-hold")) options->hold_taut_chains = false;
    else if (!std::strcmp(argv[i], "--methods") && i + 1 < argc) *only = argv[++i];
    else if (!std::strcmp(argv[i], "--adaptive") && i + 1 < argc) options->adaptive_strain = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--max-step") && i + 1 < argc) options->max_step_s = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--block-jacobi")) options->preconditioner = CgPreconditioner::block_jacobi;
    else if (!std::strcmp(argv[i], "--multigrid")) options->preconditioner = CgPreconditioner::multigrid;
    else if (!std::strcmp(argv[i], "--lines")) options->preconditioner = CgPreconditioner::lines;
    else if (!std::strcmp(argv[i], "--bending") && i + 1 < argc) {
      const auto bending = weft::base::enum_from_name(bending_in_step_names, argv[++i]);
      if (!bending) {
        std::fprintf(stderr, "--bending: expected auto, explicit or implicit, got %s\n", argv[i]);
        return false;
      }
      options->bending = *bending;
    }
    else {
      std::fprintf(stderr, "usage: %s [--sizes 32,64,128] [--step SECONDS] [--backend NAME] [--cg TOLERANCE] [--quick] [--methods SUBSTRING] [--reuse N] [--threads N] [--frames N] [--no-hold] [--adaptive STRAIN] [--max-step SECONDS] [--block-jacobi | --lines | --multigrid] [--bending auto|explicit|implicit]\n", argv[0]);
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{32, 64, 128};
  Options options;
  bool quick = false;
  std::string only;  // run only the methods whose name contains this
  if (!parse_arguments(argc, argv, &sizes, &options, &quick, &only)) return 1;
  const int cap = ProjectionSettings{}.max_iterations;
  std::vector<Method> methods{
      {"fast_projection tol 1e-2", ProjectionMethod::fast_projection, 1e-2, cap, 1.0},
      {"fast_projection tol 1e-3", ProjectionMethod::fast_projection, 1e-3, cap, 1.0},
      {"fast_projection tol 1e-4", ProjectionMethod::fast_projection, 1e-4, cap, 1.0},
      {"pairwise 10 sweeps", ProjectionMethod::pairwise, 0.0, 10, 1.0},
      {"pairwise 100 sweeps", ProjectionMethod::pairwise, 0.0, 100, 1.0},
      {"springs x1 implicit", ProjectionMethod::none, 0.0, 0, 1.0},
      {"springs x10 implicit", ProjectionMethod::none, 0.0, 0, 10.0},
      {"springs x100 implicit", ProjectionMethod::none, 0.0, 0, 100.0},
  };
  if (quick) methods = {methods[1], methods[3], methods[5]};
  if (!only.empty()) {
    std::vector<Method> kept;
    for (const Method& m : methods)
      if (m.name.find(only) != std::string::npos) kept.push_back(m);
    methods = kept;
  }
  char step[96];
  if (options.adaptive_strain > 0.0)
    std::snprintf(step, sizeof step, "adaptive to a prediction strain of %g, at most %.4g s",
                  options.adaptive_strain, options.max_step_s);
  else
    std::snprintf(step, sizeof step, "h = %.4g s", options.step_s);
  std::printf("two-corner hang, 1 m wool, %d frames at 24 fps, implicit Euler %s (%s), "
              "projection %s, top edge %s, bending %s; strain over frames after 0.5 s\n",
              options.frames, step,
              options.cg_tolerance > 0.0 ? ("CG to " + std::to_string(options.cg_tolerance)).c_str()
                                         : "direct",
              sparse_backend_name(options.backend),
              options.hold_taut_chains ? "held (taut chain)" : "projected (--no-hold)",
              weft::base::enum_name(bending_in_step_names, options.bending));
  std::printf("%-6s %-26s %10s %8s %9s %9s %8s %7s %11s %11s %7s %11s %8s\n", "size", "method", "ms/frame",
              "cpu ms", "iter/step", "fact/step", "CG/step", "max it", "max strain", "mean strain", "unconv", "steps/frame", "rejected");
  std::vector<std::pair<int, Row>> target_rows;  // fast projection at tol 1e-2, by size
  for (int n : sizes) {
    for (const Method& m : methods) {
      const Row r = run(n, m, options);
      if (m.name == "fast_projection tol 1e-2" && !r.diverged) target_rows.emplace_back(n, r);
      const std::string size = std::to_string(n) + "²";
      if (r.diverged) {
        std::printf("%-6s %-26s diverged\n", size.c_str(), m.name.c_str());
        continue;
      }
      std::printf("%-6s %-26s %10.2f %8.2f %9.2f %9.2f %8.1f %7d %10.4f%% %10.4f%% %7ld %11.2f %8ld\n", size.c_str(),
                  m.name.c_str(), r.ms_per_frame, r.cpu_ms_per_frame, r.iterations_per_step, r.factorizations_per_step, r.cg_per_step, r.max_iterations, 100 * r.max_strain, 100 * r.mean_strain,
                  r.unconverged, r.steps_per_frame, r.rejected);
      std::fflush(stdout);
    }
  }
  print_targets(target_rows);
  return 0;
}
