#pragma once
// `weft stability`: the stability map of the integrators. Sweeps the time
// step h × a stiffness scale s (every rigidity of the wool × s) on the standard cloth of
// analysis/stability.h (1 m square, n × n vertices, two corners pinned, no gravity), runs each
// integrator from a small seeded perturbation of rest, and writes
//   DIR/stability.csv        one row per integrator × s × h: stable 0/1, steps run, growth
//   DIR/critical_steps.csv   per integrator × s: ω_max, predicted, Gershgorin and observed
//                            critical steps (the table it prints)
//   DIR/stability.png        one heatmap panel per integrator: log h across, s up, light
//                            (viridis) stable, dark blew up, the predicted critical step as a
//                            line (chart/chart.h)
//   DIR/run.txt              weft version and command line
// Explicit Euler, unstable at every step without damping, runs with mass damping α = ω_max of
// each stiffness (its limit is then α/ω² = 1/ω_max); the others run undamped.

#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "sim/integrators/integrator.h"

namespace weft::app {

struct StabilityOptions {
  std::filesystem::path out = "out/stability";
  int size = 12;  // vertices per side of the standard cloth
  // Dynamic relaxation is left out: its steps are pseudo-time iterations with fictitious
  // masses scaled to be stable, so it has no critical step to map.
  std::vector<sim::Integrator> integrators = sim::physical_time_integrators();
  std::vector<double> stiffness_scales{0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0};
  int steps_per_row = 24;  // time steps h per heatmap row (log spaced)
  std::string command_line;  // recorded in run.txt
};

// Integrator names as in scene files ("rk4", ...); throws InputError naming `option` and
// listing the choices for an unknown one, or when the list is empty or repeats a name.
std::vector<sim::Integrator> parse_integrator_list(const std::vector<std::string>& names,
                                                   const std::string& option);

// Checks the options (InputError naming the option), runs the sweep with progress on stderr,
// prints the table on stdout and writes the files. Returns the exit code.
int run_stability(const StabilityOptions& options);


// Adds `weft stability` to the command line.
Command register_stability(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
