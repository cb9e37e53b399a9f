#include "app/cli/stability_command.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "app/scene/json_reader.h"
#include "app/io/output_files.h"
#include "app/io/progress.h"
#include "app/scene/scene.h"
#include "app/io/version.h"
#include "analysis/stability.h"
#include "chart/chart.h"
#include "sim/simulator.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
using sim::Integrator;

// Explicit Euler's mass damping, as a multiple of ω_max: it has no stable step undamped, and
// near its limit α/ω² a mode grows by only ½ h α (h/h_c − 1) per step, so α must be of the
// order of ω_max for a run of BlowUpSettings::steps to tell the sides apart.
constexpr double kEulerDampingRatio = 1.0;
// Steps per run. Near the limit the fastest mode grows by ≈ 2√(h/h_c − 1) per step (symplectic
// Euler; RK4 ≈ 7 (h/h_c − 1), explicit Euler ½ (h/h_c − 1) at α = ω_max), so 500 steps
// resolve the limit to ~0.1 % (explicit Euler ~4 %) at a third of a second per row.
constexpr long kStepsPerRun = 500;
// Implicit Euler factorises a sparse matrix at every step: shorter runs (it damps every mode).
constexpr long kImplicitSteps = 40;
// The swept steps span this factor below the smallest and above the largest predicted step.
constexpr double kSweepMargin = 3.0;
constexpr double kBisectionTolerance = 1e-3;  // relative width of the final bracket
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double damping_for(Integrator method, double omega_rad_s) {
  return method == Integrator::explicit_euler ? kEulerDampingRatio * omega_rad_s : 0.0;
}

analysis::BlowUpSettings blow_up_settings(Integrator method) {
  analysis::BlowUpSettings s;
  s.steps = method == Integrator::implicit_euler ? kImplicitSteps : kStepsPerRun;
  return s;
}

struct Row {  // one stiffness scale
  double scale;
  double omega_rad_s;             // √λ_max(M⁻¹K) (Lanczos)
  double gershgorin_omega_rad_s;  // the Simulator's Gershgorin bound on it
};

struct Panel {  // one integrator
  Integrator method;
  analysis::StepLimit limit = analysis::StepLimit::bounded;
  std::vector<double> predicted_h_s;   // per row; NaN unless bounded
  std::vector<double> gershgorin_h_s;  // per row: the prediction from the Gershgorin ω
  std::vector<double> observed_h_s;    // per row; NaN when not searched or not bracketed
  std::vector<std::vector<analysis::BlowUpResult>> runs;  // [row][column]
  bool all_stable() const {
    for (const auto& row : runs)
      for (const auto& r : row)
        if (!r.stable) return false;
    return true;
  }
};

void check_options(const StabilityOptions& o) {
  if (o.size < 3 || o.size > 48)
    throw InputError("--size: expected 3..48 vertices per side, got " + std::to_string(o.size));
  if (o.steps_per_row < 2 || o.steps_per_row > 200)
    throw InputError("--steps-per-row: expected 2..200, got " + std::to_string(o.steps_per_row));
  if (o.integrators.empty()) throw InputError("--integrators: expected at least one integrator");
  if (o.stiffness_scales.empty() || o.stiffness_scales.size() > 40)
    throw InputError("--stiffness-scales: expected 1..40 values");
  for (double s : o.stiffness_scales)
    if (!(s >= 1e-4 && s <= 1e4))
      throw InputError("--stiffness-scales: expected values in 1e-4..1e4, got " + std::to_string(s));
}

std::string format_g(double value, int digits = 4) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

// ---- the heatmap -------------------------------------------------------------------------

// Colour-blind-safe cells: two well-separated stops of viridis (chart/palette.h).
const chart::Rgb8 kStable = chart::viridis(0.9), kBlewUp = chart::viridis(0.3);

// The predicted critical step: through the row centres, extended to the plot's edges (rows
// run from 0 at the bottom to rows at the top), as a white-haloed black line.
std::vector<chart::Series> predicted_line(const Panel& panel, const chart::Axis& x) {
  std::vector<double> hs, ys;
  for (std::size_t r = 0; r < panel.predicted_h_s.size(); ++r)
    if (std::isfinite(panel.predicted_h_s[r])) {
      hs.push_back(std::log(panel.predicted_h_s[r]));
      ys.push_back(static_cast<double>(r) + 0.5);
    }
  if (hs.empty()) return {};
  const double rows = static_cast<double>(panel.predicted_h_s.size());
  const auto extend = [&](std::size_t a, std::size_t b, double y) {  // in log h, clamped
    const double lh = hs[a] + (hs[b] - hs[a]) * (y - ys[a]) / (ys[b] - ys[a]);
    return std::clamp(std::exp(lh), x.lo, x.hi);
  };
  std::vector<double> line_h, line_y;
  if (hs.size() == 1) {
    line_h = {std::exp(hs[0]), std::exp(hs[0])};
    line_y = {0.0, rows};
  } else {
    line_h.push_back(extend(0, 1, 0.0));
    line_y.push_back(0.0);
    for (std::size_t k = 0; k < hs.size(); ++k) {
      line_h.push_back(std::exp(hs[k]));
      line_y.push_back(ys[k]);
    }
    line_h.push_back(extend(hs.size() - 2, hs.size() - 1, rows));
    line_y.push_back(rows);
  }
  chart::Series halo{"predicted_halo", chart::kWhite, line_h, line_y, 4.0};
  chart::Series line{"predicted", chart::okabe_ito::black, line_h, line_y, 2.0};
  return {halo, line};
}

chart::Plot heatmap_panel(const Panel& panel, const std::vector<Row>& rows,
                          const std::vector<double>& h_s, double h_lo, double h_hi) {
  chart::Plot plot;
  plot.title = sim::integrator_name(panel.method);
  if (panel.method == Integrator::explicit_euler) plot.note = "(α = ω_max)";
  if (panel.limit == analysis::StepLimit::always_stable)
    plot.note = panel.all_stable() ? "(stable everywhere)" : "(NOT stable everywhere)";
  plot.x = {"time step h [s]", chart::Scale::log, h_lo, h_hi};
  plot.y = {"stiffness scale s", chart::Scale::linear, 0.0, static_cast<double>(rows.size())};
  for (std::size_t r = 0; r < rows.size(); ++r)
    plot.y.ticks.push_back({static_cast<double>(r) + 0.5, format_g(rows[r].scale, 3)});
  const double n = static_cast<double>(h_s.size()), ratio = h_hi / h_lo;
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t j = 0; j < h_s.size(); ++j)
      plot.cells.push_back({h_lo * std::pow(ratio, static_cast<double>(j) / n),
                            h_lo * std::pow(ratio, static_cast<double>(j + 1) / n),
                            static_cast<double>(r), static_cast<double>(r + 1),
                            panel.runs[r][j].stable ? kStable : kBlewUp});
  plot.series = predicted_line(panel, plot.x);
  chart::Series observed{"observed", chart::okabe_ito::black, {}, {}, 0.0};
  observed.marker = chart::Marker::ring;
  for (std::size_t r = 0; r < rows.size(); ++r)  // observed critical steps (bisection)
    if (std::isfinite(panel.observed_h_s[r])) {
      observed.x.push_back(panel.observed_h_s[r]);
      observed.y.push_back(static_cast<double>(r) + 0.5);
    }
  plot.series.push_back(observed);
  return plot;
}

chart::Figure heatmap(const std::string& title, const std::vector<Row>& rows,
                      const std::vector<Panel>& panels, const std::vector<double>& h_s,
                      double h_lo, double h_hi) {
  chart::Figure figure;
  figure.title = title;
  figure.subtitle = "each cell: one run from a seeded perturbation of rest; blew up = "
                    "displacement ×1000 or non-finite";
  for (const Panel& p : panels) figure.plots.push_back(heatmap_panel(p, rows, h_s, h_lo, h_hi));
  figure.columns = 3;
  figure.plot_width = std::max(4, 300 / static_cast<int>(h_s.size())) * static_cast<int>(h_s.size());
  figure.plot_height = std::max(6, 180 / static_cast<int>(rows.size())) * static_cast<int>(rows.size());
  using chart::Swatch;
  figure.legend = {{"stable", Swatch::box, kStable},
                   {"blew up", Swatch::box, kBlewUp},
                   {"predicted critical step", Swatch::line, chart::okabe_ito::black},
                   {"observed (bisection)", Swatch::ring, chart::okabe_ito::black}};
  return figure;
}

// ---- the sweep ---------------------------------------------------------------------------

std::string format_e(double value) {
  if (!std::isfinite(value)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.6e", value);
  return text;
}

}  // namespace

std::vector<Integrator> parse_integrator_list(const std::vector<std::string>& names,
                                              const std::string& option) {
  if (names.empty()) throw InputError(option + ": expected at least one integrator");
  std::vector<Integrator> result;
  for (const std::string& name : names) {
    const std::vector<Integrator> known = sim::physical_time_integrators();
    const auto it = std::find_if(known.begin(), known.end(),
                                 [&](Integrator i) { return name == sim::integrator_name(i); });
    if (name == sim::integrator_name(Integrator::dynamic_relaxation)) {
      throw InputError(option + ": 'dynamic_relaxation' iterates toward the static equilibrium "
                       "in pseudo-time with masses scaled to be stable: it has no critical step");
    }
    if (it == known.end()) {
      std::string choices;
      for (Integrator i : known)
        choices += std::string(choices.empty() ? "'" : ", '") + sim::integrator_name(i) + "'";
      throw InputError(option + ": unknown integrator '" + name + "'; expected one of " + choices);
    }
    if (std::find(result.begin(), result.end(), *it) != result.end())
      throw InputError(option + ": '" + name + "' is listed twice");
    result.push_back(*it);
  }
  return result;
}

namespace {

// The rows: one cloth per stiffness scale, its ω_max (Lanczos) and Gershgorin bound.
std::vector<Row> measure_rows(const std::vector<double>& scales,
                              const std::vector<std::unique_ptr<analysis::StabilityCloth>>& cloths) {
  std::vector<Row> rows;
  for (std::size_t r = 0; r < scales.size(); ++r) {
    const analysis::StabilityCloth& cloth = *cloths[r];
    const analysis::LargestEigenvalue e = cloth.largest_eigenvalue();
    if (!e.converged)
      std::fprintf(stderr, "weft: warning: s = %g: lambda_max not converged in %d steps\n",
                   scales[r], e.iterations);
    const double gershgorin_h =
        sim::Simulator(cloth.mesh(), cloth.material(), cloth.pinned(), sim::SimSettings{})
            .critical_time_step();
    rows.push_back({scales[r], e.omega_rad_s(), 2.0 / gershgorin_h});
  }
  return rows;
}

// The swept steps: log spaced over [h_lo, h_hi], at the cells' centres.
struct Steps {
  double lo = 0.0, hi = 0.0;
  std::vector<double> h_s;
};

// The panels' predictions, and the swept steps around them.
std::vector<Panel> predict_panels(const std::vector<Integrator>& integrators,
                                  const std::vector<Row>& rows, int steps_per_row, Steps& steps) {
  std::vector<Panel> panels;
  double h_min = std::numeric_limits<double>::infinity(), h_max = 0.0;
  for (Integrator method : integrators) {
    Panel p;
    p.method = method;
    for (const Row& row : rows) {
      const double alpha = damping_for(method, row.omega_rad_s);
      const analysis::CriticalStep predicted = analysis::predicted_critical_step(method, row.omega_rad_s, alpha);
      p.limit = predicted.limit;
      const bool bounded = predicted.limit == analysis::StepLimit::bounded;
      p.predicted_h_s.push_back(bounded ? predicted.h_s : kNaN);
      p.gershgorin_h_s.push_back(
          bounded ? analysis::predicted_critical_step(method, row.gershgorin_omega_rad_s, alpha).h_s
                  : kNaN);
      const double reference = bounded ? predicted.h_s : 2.0 / row.omega_rad_s;
      h_min = std::min(h_min, reference);
      h_max = std::max(h_max, reference);
    }
    panels.push_back(std::move(p));
  }
  steps.lo = h_min / kSweepMargin;
  steps.hi = h_max * kSweepMargin;
  steps.h_s.resize(static_cast<std::size_t>(steps_per_row));
  const double n = static_cast<double>(steps.h_s.size());
  for (std::size_t j = 0; j < steps.h_s.size(); ++j)
    steps.h_s[j] = steps.lo * std::pow(steps.hi / steps.lo, (static_cast<double>(j) + 0.5) / n);
  return panels;
}

// Every cell's blow-up run, and the observed critical step of each bounded row (bisection).
void run_panels(std::vector<Panel>& panels, const std::vector<Row>& rows,
                const std::vector<std::unique_ptr<analysis::StabilityCloth>>& cloths,
                const std::vector<double>& h_s, Progress& progress) {
  int done = 0;
  for (Panel& p : panels) {
    p.runs.resize(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double alpha = damping_for(p.method, rows[r].omega_rad_s);
      const analysis::StepperFactory make = cloths[r]->stepper_factory(p.method, alpha);
      const analysis::BlowUpSettings settings = blow_up_settings(p.method);
      const analysis::StabilityCloth& cloth = *cloths[r];
      for (double h : h_s)
        p.runs[r].push_back(analysis::run_blow_up_test(make(), cloth.rest_positions(), cloth.mass_kg(),
                                                  cloth.inv_mass(), h, settings));
      double observed = kNaN;
      if (p.limit == analysis::StepLimit::bounded) {
        const analysis::CriticalStepSearch search =
            analysis::find_critical_step(make, cloth.rest_positions(), cloth.mass_kg(),
                                    cloth.inv_mass(), p.predicted_h_s[r], settings,
                                    kBisectionTolerance);
        if (search.bracketed) observed = search.h_s();
      }
      p.observed_h_s.push_back(observed);
      progress.update(++done, std::string(sim::integrator_name(p.method)) + " s = " +
                                  format_g(rows[r].scale, 3));
    }
  }
}

// The rows' eigenvalues as the table's first part.
void write_row_table(std::ostream& table, const std::vector<Row>& rows) {
  table << "  scale s   omega_max (rad/s)   2/omega_max (s)   Gershgorin 2/omega (s)   Gershgorin/exact\n";
  for (const Row& row : rows) {
    char line[160];
    std::snprintf(line, sizeof line, "  %7.3g   %17.5e   %15.5e   %22.5e   %16.3f\n", row.scale,
                  row.omega_rad_s, 2.0 / row.omega_rad_s, 2.0 / row.gershgorin_omega_rad_s,
                  row.omega_rad_s / row.gershgorin_omega_rad_s);
    table << line;
  }
}

// The table (stdout and critical_steps.csv) and the full sweep (stability.csv).
void write_tables(const StabilityOptions& options, const std::string& cloth_text,
                  const std::vector<Row>& rows, const std::vector<Panel>& panels,
                  const std::vector<double>& h_s) {
  std::ostringstream table, critical_csv, sweep_csv;
  table << "stability of the standard cloth: " << cloth_text << "\n\n";
  write_row_table(table, rows);
  table << "\n  integrator           scale s   predicted h (s)   observed h (s)   observed/predicted\n";
  critical_csv << "integrator,stiffness_scale,omega_max_rad_s,damping_1_s,predicted_h_s,"
                  "gershgorin_h_s,observed_h_s,observed_over_predicted\n";
  sweep_csv << "integrator,stiffness_scale,h_s,predicted_h_s,stable,steps_run,max_growth\n";
  for (const Panel& p : panels) {
    const std::string name = sim::integrator_name(p.method);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double predicted = p.predicted_h_s[r], observed = p.observed_h_s[r];
      char line[200];
      if (p.limit == analysis::StepLimit::always_stable) {
        long stable = 0;
        for (const auto& run : p.runs[r]) stable += run.stable;
        std::snprintf(line, sizeof line, "  %-18s   %7.3g   %15s   stable at %ld of %zu steps (%ld steps each)\n",
                      name.c_str(), rows[r].scale, "no limit", stable, p.runs[r].size(),
                      kImplicitSteps);
      } else {
        std::snprintf(line, sizeof line, "  %-18s   %7.3g   %15.5e   %14.5e   %18.4f\n",
                      name.c_str(), rows[r].scale, predicted, observed, observed / predicted);
      }
      table << line;
      critical_csv << name << ',' << rows[r].scale << ',' << format_e(rows[r].omega_rad_s) << ','
                   << format_e(damping_for(p.method, rows[r].omega_rad_s)) << ','
                   << format_e(predicted) << ',' << format_e(p.gershgorin_h_s[r]) << ','
                   << format_e(observed) << ',' << format_e(observed / predicted) << '\n';
      for (std::size_t j = 0; j < h_s.size(); ++j) {
        const analysis::BlowUpResult& run = p.runs[r][j];
        sweep_csv << name << ',' << rows[r].scale << ',' << format_e(h_s[j]) << ','
                  << format_e(predicted) << ',' << (run.stable ? 1 : 0) << ',' << run.steps_run
                  << ',' << format_e(run.max_growth) << '\n';
      }
    }
  }
  std::fputs(table.str().c_str(), stdout);
  write_text(options.out / "critical_steps.csv", critical_csv.str());
  write_text(options.out / "stability.csv", sweep_csv.str());
}

}  // namespace

int run_stability(const StabilityOptions& options) {
  check_options(options);
  std::vector<double> scales = options.stiffness_scales;
  std::sort(scales.begin(), scales.end());
  if (std::adjacent_find(scales.begin(), scales.end()) != scales.end())
    throw InputError("--stiffness-scales: a value is listed twice");
  fs::create_directories(options.out);

  std::vector<std::unique_ptr<analysis::StabilityCloth>> cloths;
  for (double s : scales) cloths.push_back(std::make_unique<analysis::StabilityCloth>(options.size, s));
  const std::vector<Row> rows = measure_rows(scales, cloths);
  Steps steps;
  std::vector<Panel> panels = predict_panels(options.integrators, rows, options.steps_per_row, steps);

  const std::string cloth_text = std::to_string(options.size) + "x" +
                                 std::to_string(options.size) +
                                 " wool (Kang & Yu), 1 m square, corners u0v1 u1v1 pinned, no "
                                 "gravity, all rigidities x s";
  std::fprintf(stderr, "weft: stability of %s: %zu integrators x %zu scales x %zu steps\n",
               cloth_text.c_str(), panels.size(), rows.size(), steps.h_s.size());
  Progress progress(stderr, static_cast<int>(panels.size() * rows.size()), "stability");
  run_panels(panels, rows, cloths, steps.h_s, progress);
  progress.finish();

  write_tables(options, cloth_text, rows, panels, steps.h_s);
  write_text(options.out / "run.txt", "weft " + std::string(version()) +
                                          "\ncommand: " + options.command_line + "\n");
  chart::write_png(heatmap("weft stability: " + cloth_text, rows, panels, steps.h_s, steps.lo,
                           steps.hi),
                   options.out / "stability.png");
  std::fprintf(stderr, "weft: wrote %s (stability.png, stability.csv, critical_steps.csv) in %s\n",
               options.out.c_str(), format_duration(progress.elapsed_s()).c_str());
  return 0;
}

Command register_stability(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<StabilityOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "stability", "Sweep time step x stiffness for each integrator; write stability.png/.csv");
  cmd->add_option("--out", o->out, "Output folder (default: out/stability)");
  check_range(cmd->add_option("--size", o->size, "Vertices per side of the 1 m cloth (default 12)"),
              Range::closed(3, 48));
  cmd->add_option_function<std::vector<std::string>>(
         "--integrators",
         [o](const std::vector<std::string>& names) {
           o->integrators = parse_integrator_list(names, "--integrators");
         },
         "Comma-separated integrators (default: all)")
      ->delimiter(',');
  check_range(cmd->add_option("--stiffness-scales", o->stiffness_scales,
                              "Comma-separated factors on every rigidity (default "
                              "0.1,0.3,1,3,10,30,100)")
                  ->delimiter(','),
              Range::closed(1e-4, 1e4));
  check_range(cmd->add_option("--steps-per-row", o->steps_per_row,
                              "Time steps h per heatmap row, log spaced (default 24)"),
              Range::closed(2, 200));
  return {cmd, [o] { return run_stability(*o); }};
}

}  // namespace weft::app
