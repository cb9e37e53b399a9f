// The rest shape three ways — the static equilibrium solver (Newton), dynamic relaxation and the
// scene's own damped dynamics — on a hang, a cantilever, a disc drape and the Cusick drape: CPU
// time of each, the drape coefficient and folds, and how far each rest shape lies from the
// static one (docs/models.md, "Static equilibrium"). Prints one table; no timing is asserted.
//
//   build/bench/static_rest_bench [--scenes a,b,...] [--max-simulated-s 60]

#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/fit/fit_problem.h"
#include "app/run/measure.h"
#include "app/run/rest_shape.h"
#include "app/scene/scene.h"

namespace {

using namespace weft;

double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Row {
  std::string method;
  double cpu_s = 0.0;
  bool rested = false;
  std::string detail;  // iterations, simulated time
  std::optional<analysis::DrapeShape> drape;
  sim::Matrix3X x;
};

std::optional<analysis::DrapeShape> drape_of(const app::Scene& scene, const sim::Simulator& s) {
  const auto support = app::scene_support(scene, s.mesh(), false);
  if (!support) return std::nullopt;
  return analysis::measure_drape(s.mesh(), s.mesh().triangles(), s.state().x, *support);
}

Row static_row(const app::Scene& scene) {
  Row r;
  r.method = "static (Newton)";
  const double start = cpu_now();
  const app::RestShape rest = app::solve_rest_shape(scene);
  r.cpu_s = cpu_now() - start;
  r.rested = rest.solve.converged;
  r.detail = std::to_string(rest.solve.iterations) + " iterations";
  r.drape = drape_of(scene, *rest.simulator);
  r.x = rest.simulator->state().x;
  return r;
}

Row relaxation_row(const app::Scene& scene) {
  Row r;
  r.method = "dynamic relaxation";
  app::SettleSettings settings;
  settings.method = app::SettleMethod::dynamic_relaxation;
  const double start = cpu_now();
  const app::Settled s = app::settle_to_rest(scene, settings);
  r.cpu_s = cpu_now() - start;
  r.rested = s.converged;
  r.detail = std::to_string(s.iterations) + " iterations";
  r.drape = drape_of(scene, *s.simulator);
  r.x = s.simulator->state().x;
  return r;
}

// The scene's integrator and damping, frame by frame until the fastest vertex has stayed below
// 1 mm/s for 1 s of simulated time (at most max_s).
Row dynamics_row(const app::Scene& scene, double max_s) {
  Row r;
  r.method = "damped dynamics";
  const double start = cpu_now();
  const auto simulator = app::make_simulator(scene);
  const double frame_s = 1.0 / scene.fps;
  double still_since = 0.0, t = 0.0;
  while (t < max_s) {
    simulator->advance(frame_s);
    t += frame_s;
    if (simulator->diagnostics().max_speed_m_s >= 1e-3) still_since = t;
    if (t - still_since >= 1.0) {
      r.rested = true;
      break;
    }
  }
  r.cpu_s = cpu_now() - start;
  char text[64];
  std::snprintf(text, sizeof text, "%.2f s simulated", t);
  r.detail = text;
  r.drape = drape_of(scene, *simulator);
  r.x = simulator->state().x;
  return r;
}

void print_row(const Row& r, const Row& reference) {
  const double max_d = (r.x - reference.x).rowwise().norm().maxCoeff();
  const double rms_d = std::sqrt((r.x - reference.x).rowwise().squaredNorm().mean());
  std::printf("  %-20s %9.2f %8.2fx %-4s %-22s", r.method.c_str(), r.cpu_s,
              r.cpu_s / reference.cpu_s, r.rested ? "yes" : "NO", r.detail.c_str());
  if (r.drape) std::printf(" DC %.3f, %2d folds", r.drape->drape_coefficient, r.drape->folds);
  else std::printf(" %17s", "");
  std::printf("   shape vs static: max %7.2f mm, rms %6.2f mm\n", 1e3 * max_d, 1e3 * rms_d);
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream s(text);
  for (std::string p; std::getline(s, p, ',');) parts.push_back(p);
  return parts;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes = {"hang_corners_20", "bendstiff_strip", "disc_drape_50",
                                     "cusick_drape"};
  double max_s = 60.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--scenes") scenes = split(argv[i + 1]);
    else if (flag == "--max-simulated-s") max_s = std::stod(argv[i + 1]);
  }
  std::printf("rest shapes: CPU s, ratio to the static solve, rested, work, drape, distance to the "
              "static rest shape\n");
  for (const std::string& name : scenes) {
    const app::Scene scene =
        app::load_scene(std::string(WEFT_SOURCE_DIR) + "/assets/scenes/" + name + ".json");
    std::printf("%s (%s)\n", name.c_str(), app::cloth_size_text(scene).c_str());
    const Row statics = static_row(scene);
    print_row(statics, statics);
    print_row(relaxation_row(scene), statics);
    print_row(dynamics_row(scene, max_s), statics);
    std::fflush(stdout);
  }
  return 0;
}
