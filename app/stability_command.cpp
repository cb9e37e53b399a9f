#include "app/stability_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "app/output_files.h"
#include "app/progress.h"
#include "app/scene.h"
#include "app/version.h"
#include "render/canvas.h"
#include "sim/simulator.h"
#include "analysis/stability.h"

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

sim::BlowUpSettings blow_up_settings(Integrator method) {
  sim::BlowUpSettings s;
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
  sim::StepLimit limit = sim::StepLimit::bounded;
  std::vector<double> predicted_h_s;   // per row; NaN unless bounded
  std::vector<double> gershgorin_h_s;  // per row: the prediction from the Gershgorin ω
  std::vector<double> observed_h_s;    // per row; NaN when not searched or not bracketed
  std::vector<std::vector<sim::BlowUpResult>> runs;  // [row][column]
  bool all_stable() const {
    for (const auto& row : runs)
      for (const auto& r : row)
        if (!r.stable) return false;
    return true;
  }
};

void check_options(const StabilityOptions& o) {
  if (o.size < 3 || o.size > 48)
    throw SceneError("--size: expected 3..48 vertices per side, got " + std::to_string(o.size));
  if (o.steps_per_row < 2 || o.steps_per_row > 200)
    throw SceneError("--steps-per-row: expected 2..200, got " + std::to_string(o.steps_per_row));
  if (o.integrators.empty()) throw SceneError("--integrators: expected at least one integrator");
  if (o.stiffness_scales.empty() || o.stiffness_scales.size() > 40)
    throw SceneError("--stiffness-scales: expected 1..40 values");
  for (double s : o.stiffness_scales)
    if (!(s >= 1e-4 && s <= 1e4))
      throw SceneError("--stiffness-scales: expected values in 1e-4..1e4, got " + std::to_string(s));
}

std::string format_g(double value, int digits = 4) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

// ---- the heatmap -------------------------------------------------------------------------

const render::Rgb8 kWhite{255, 255, 255}, kBlack{0, 0, 0}, kGrey{110, 110, 110};
const render::Rgb8 kStable{70, 165, 90}, kBlewUp{210, 70, 60};

// A tick label for h = mantissa × 10^exponent: "1e-4", "2e-4".
std::string tick_label(int mantissa, int exponent) {
  return std::to_string(mantissa) + "e" + std::to_string(exponent);
}

struct Layout {
  int cell_w, cell_h, plot_w, plot_h;
  int panel_w, panel_h;
  static constexpr int kLeft = 62, kRight = 14, kTop = 30, kBottom = 42;
};

void draw_panel(render::Canvas& c, int x0, int y0, const Layout& L, const Panel& panel,
                const std::vector<Row>& rows, const std::vector<double>& h_s, double h_lo,
                double h_hi) {
  const int left = x0 + Layout::kLeft, top = y0 + Layout::kTop;
  const int right = left + L.plot_w, bottom = top + L.plot_h;
  const double log_span = std::log(h_hi / h_lo);
  const auto x_of = [&](double h) { return left + L.plot_w * std::log(h / h_lo) / log_span; };
  const auto y_centre = [&](std::size_t r) {  // row 0 (the smallest scale) at the bottom
    return bottom - L.cell_h * (static_cast<double>(r) + 0.5);
  };
  const int th = render::Canvas::text_height();

  // The name in double size, a note after it in single size on the same baseline.
  const std::string name = sim::integrator_name(panel.method);
  std::string note;
  if (panel.method == Integrator::explicit_euler) note = "(alpha = omega_max)";
  if (panel.limit == sim::StepLimit::always_stable)
    note = panel.all_stable() ? "(stable everywhere)" : "(NOT stable everywhere)";
  const int title_y = y0 + (Layout::kTop - 2 * th) / 2;
  c.text(left, title_y, name, kBlack, 2);
  c.text(left + render::Canvas::text_width(name, 2) + 8, title_y + th, note, kBlack);

  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t j = 0; j < h_s.size(); ++j) {
      const int cx = left + static_cast<int>(j) * L.cell_w;
      const int cy = bottom - static_cast<int>(r + 1) * L.cell_h;
      c.fill_rect(cx, cy, cx + L.cell_w, cy + L.cell_h, panel.runs[r][j].stable ? kStable : kBlewUp);
    }
    const std::string label = format_g(rows[r].scale, 3);
    c.text(left - 6 - render::Canvas::text_width(label), static_cast<int>(y_centre(r)) - th / 2,
           label, kBlack);
  }
  c.rect(left - 1, top - 1, right + 1, bottom + 1, kBlack);

  // x ticks at 1, 2, 5 × 10^e inside [h_lo, h_hi] (decades only when they are enough).
  const int e_lo = static_cast<int>(std::floor(std::log10(h_lo)));
  const int e_hi = static_cast<int>(std::ceil(std::log10(h_hi)));
  const bool decades_only = e_hi - e_lo >= 3;
  for (int e = e_lo; e <= e_hi; ++e) {
    for (int m : {1, 2, 5}) {
      if (decades_only && m != 1) continue;
      const double h = m * std::pow(10.0, e);
      if (h < h_lo || h > h_hi) continue;
      const double x = x_of(h);
      c.line(x, bottom + 1, x, bottom + 5, kBlack);
      const std::string label = tick_label(m, e);
      c.text(static_cast<int>(x) - render::Canvas::text_width(label) / 2, bottom + 8, label, kBlack);
    }
  }
  const std::string x_label = "time step h (s), log scale";
  c.text(left + (L.plot_w - render::Canvas::text_width(x_label)) / 2, bottom + 12 + th + 4,
         x_label, kGrey);
  const std::string y_label = "stiffness scale s";
  c.text_vertical(x0 + 6, top + (L.plot_h + render::Canvas::text_width(y_label)) / 2, y_label,
                  kGrey);

  // The predicted critical step: through the row centres, extended to the plot's edges.
  std::vector<std::pair<double, double>> points;
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (std::isfinite(panel.predicted_h_s[r]))
      points.emplace_back(x_of(panel.predicted_h_s[r]), y_centre(r));
  if (!points.empty()) {
    const auto extend = [&](std::pair<double, double> a, std::pair<double, double> b, double y) {
      const double x = a.first + (b.first - a.first) * (y - a.second) / (b.second - a.second);
      return std::pair<double, double>(std::clamp(x, double(left), double(right)), y);
    };
    if (points.size() == 1) {
      c.line(points[0].first, top, points[0].first, bottom, kBlack, 2);
    } else {
      const auto first = extend(points[0], points[1], bottom);
      const auto last = extend(points[points.size() - 2], points.back(), top);
      points.insert(points.begin(), first);
      points.push_back(last);
      for (std::size_t k = 0; k + 1 < points.size(); ++k)
        c.line(points[k].first, points[k].second, points[k + 1].first, points[k + 1].second,
               kBlack, 2);
    }
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {  // observed critical steps (bisection)
    if (!std::isfinite(panel.observed_h_s[r])) continue;
    const double x = x_of(panel.observed_h_s[r]), y = y_centre(r);
    c.circle(x, y, 4.0, kWhite, true);
    c.circle(x, y, 4.0, kBlack, false);
  }
}

void write_heatmap(const fs::path& path, const std::string& title, const std::vector<Row>& rows,
                   const std::vector<Panel>& panels, const std::vector<double>& h_s, double h_lo,
                   double h_hi) {
  Layout L{};
  L.cell_w = std::max(4, 300 / static_cast<int>(h_s.size()));
  L.cell_h = std::max(6, 180 / static_cast<int>(rows.size()));
  L.plot_w = L.cell_w * static_cast<int>(h_s.size());
  L.plot_h = L.cell_h * static_cast<int>(rows.size());
  L.panel_w = Layout::kLeft + L.plot_w + Layout::kRight;
  L.panel_h = Layout::kTop + L.plot_h + Layout::kBottom;
  const int columns = std::min<int>(3, static_cast<int>(panels.size()));
  const int panel_rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  const int header = 16 + 2 * render::Canvas::text_height() + 12, footer = 40;
  const int width = std::max(columns * L.panel_w + 20, 560);
  render::Canvas c(width, header + panel_rows * L.panel_h + footer, kWhite);
  c.text(10, 10, title, kBlack, 1);
  c.text(10, 10 + render::Canvas::text_height() + 6,
         "each cell: one run from a seeded perturbation of rest; blew up = displacement x1000 or "
         "non-finite",
         kGrey, 1);
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const int col = static_cast<int>(p) % columns, prow = static_cast<int>(p) / columns;
    draw_panel(c, 10 + col * L.panel_w, header + prow * L.panel_h, L, panels[p], rows, h_s, h_lo,
               h_hi);
  }
  // Legend.
  const int ly = header + panel_rows * L.panel_h + 12, th = render::Canvas::text_height();
  int lx = 10 + Layout::kLeft;
  const auto legend_text = [&](const std::string& s) {
    c.text(lx, ly + (12 - th) / 2, s, kBlack);
    lx += render::Canvas::text_width(s) + 24;
  };
  c.fill_rect(lx, ly, lx + 12, ly + 12, kStable);
  lx += 18;
  legend_text("stable");
  c.fill_rect(lx, ly, lx + 12, ly + 12, kBlewUp);
  lx += 18;
  legend_text("blew up");
  c.line(lx, ly + 6, lx + 24, ly + 6, kBlack, 2);
  lx += 30;
  legend_text("predicted critical step");
  c.circle(lx + 5, ly + 6, 4.0, kWhite, true);
  c.circle(lx + 5, ly + 6, 4.0, kBlack, false);
  lx += 16;
  legend_text("observed (bisection)");
  render::write_png(c.image(), path);
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
  if (names.empty()) throw SceneError(option + ": expected at least one integrator");
  std::vector<Integrator> result;
  for (const std::string& name : names) {
    const std::vector<Integrator> known = sim::physical_time_integrators();
    const auto it = std::find_if(known.begin(), known.end(),
                                 [&](Integrator i) { return name == sim::integrator_name(i); });
    if (name == sim::integrator_name(Integrator::dynamic_relaxation)) {
      throw SceneError(option + ": 'dynamic_relaxation' iterates toward the static equilibrium "
                       "in pseudo-time with masses scaled to be stable: it has no critical step");
    }
    if (it == known.end()) {
      std::string choices;
      for (Integrator i : known)
        choices += std::string(choices.empty() ? "'" : ", '") + sim::integrator_name(i) + "'";
      throw SceneError(option + ": unknown integrator '" + name + "'; expected one of " + choices);
    }
    if (std::find(result.begin(), result.end(), *it) != result.end())
      throw SceneError(option + ": '" + name + "' is listed twice");
    result.push_back(*it);
  }
  return result;
}

int run_stability(const StabilityOptions& options) {
  check_options(options);
  std::vector<double> scales = options.stiffness_scales;
  std::sort(scales.begin(), scales.end());
  if (std::adjacent_find(scales.begin(), scales.end()) != scales.end())
    throw SceneError("--stiffness-scales: a value is listed twice");
  fs::create_directories(options.out);

  // The rows: one cloth per stiffness scale, its ω_max (Lanczos) and Gershgorin bound.
  std::vector<std::unique_ptr<sim::StabilityCloth>> cloths;
  std::vector<Row> rows;
  for (double s : scales) {
    cloths.push_back(std::make_unique<sim::StabilityCloth>(options.size, s));
    const sim::StabilityCloth& cloth = *cloths.back();
    const sim::LargestEigenvalue e = cloth.largest_eigenvalue();
    if (!e.converged)
      std::fprintf(stderr, "weft: warning: s = %g: lambda_max not converged in %d steps\n", s,
                   e.iterations);
    const double gershgorin_h =
        sim::Simulator(cloth.mesh(), cloth.material(), cloth.pinned(), sim::SimSettings{})
            .critical_time_step();
    rows.push_back({s, e.omega_rad_s(), 2.0 / gershgorin_h});
  }

  // The panels' predictions, and the swept steps around them.
  std::vector<Panel> panels;
  double h_min = std::numeric_limits<double>::infinity(), h_max = 0.0;
  for (Integrator method : options.integrators) {
    Panel p;
    p.method = method;
    for (const Row& row : rows) {
      const double alpha = damping_for(method, row.omega_rad_s);
      const sim::CriticalStep predicted = sim::predicted_critical_step(method, row.omega_rad_s, alpha);
      p.limit = predicted.limit;
      const bool bounded = predicted.limit == sim::StepLimit::bounded;
      p.predicted_h_s.push_back(bounded ? predicted.h_s : kNaN);
      p.gershgorin_h_s.push_back(
          bounded ? sim::predicted_critical_step(method, row.gershgorin_omega_rad_s, alpha).h_s
                  : kNaN);
      const double reference = bounded ? predicted.h_s : 2.0 / row.omega_rad_s;
      h_min = std::min(h_min, reference);
      h_max = std::max(h_max, reference);
    }
    panels.push_back(std::move(p));
  }
  const double h_lo = h_min / kSweepMargin, h_hi = h_max * kSweepMargin;
  std::vector<double> h_s(static_cast<std::size_t>(options.steps_per_row));
  for (std::size_t j = 0; j < h_s.size(); ++j)  // cell centres, log spaced
    h_s[j] = h_lo * std::pow(h_hi / h_lo, (static_cast<double>(j) + 0.5) / static_cast<double>(h_s.size()));

  const std::string cloth_text = std::to_string(options.size) + "x" +
                                 std::to_string(options.size) +
                                 " wool (Kang & Yu), 1 m square, corners u0v1 u1v1 pinned, no "
                                 "gravity, all rigidities x s";
  std::fprintf(stderr, "weft: stability of %s: %zu integrators x %zu scales x %zu steps\n",
               cloth_text.c_str(), panels.size(), rows.size(), h_s.size());
  Progress progress(stderr, static_cast<int>(panels.size() * rows.size()), "stability");
  int done = 0;
  for (Panel& p : panels) {
    p.runs.resize(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double alpha = damping_for(p.method, rows[r].omega_rad_s);
      const sim::StepperFactory make = cloths[r]->stepper_factory(p.method, alpha);
      const sim::BlowUpSettings settings = blow_up_settings(p.method);
      const sim::StabilityCloth& cloth = *cloths[r];
      for (double h : h_s)
        p.runs[r].push_back(sim::run_blow_up_test(make(), cloth.rest_positions(), cloth.mass_kg(),
                                                  cloth.inv_mass(), h, settings));
      double observed = kNaN;
      if (p.limit == sim::StepLimit::bounded) {
        const sim::CriticalStepSearch search =
            sim::find_critical_step(make, cloth.rest_positions(), cloth.mass_kg(),
                                    cloth.inv_mass(), p.predicted_h_s[r], settings,
                                    kBisectionTolerance);
        if (search.bracketed) observed = search.h_s();
      }
      p.observed_h_s.push_back(observed);
      progress.update(++done, std::string(sim::integrator_name(p.method)) + " s = " +
                                  format_g(rows[r].scale, 3));
    }
  }
  progress.finish();

  // The table (stdout and critical_steps.csv) and the full sweep (stability.csv).
  std::ostringstream table, critical_csv, sweep_csv;
  table << "stability of the standard cloth: " << cloth_text << "\n\n"
        << "  scale s   omega_max (rad/s)   2/omega_max (s)   Gershgorin 2/omega (s)   Gershgorin/exact\n";
  for (const Row& row : rows) {
    char line[160];
    std::snprintf(line, sizeof line, "  %7.3g   %17.5e   %15.5e   %22.5e   %16.3f\n", row.scale,
                  row.omega_rad_s, 2.0 / row.omega_rad_s, 2.0 / row.gershgorin_omega_rad_s,
                  row.omega_rad_s / row.gershgorin_omega_rad_s);
    table << line;
  }
  table << "\n  integrator           scale s   predicted h (s)   observed h (s)   observed/predicted\n";
  critical_csv << "integrator,stiffness_scale,omega_max_rad_s,damping_1_s,predicted_h_s,"
                  "gershgorin_h_s,observed_h_s,observed_over_predicted\n";
  sweep_csv << "integrator,stiffness_scale,h_s,predicted_h_s,stable,steps_run,max_growth\n";
  for (const Panel& p : panels) {
    const std::string name = sim::integrator_name(p.method);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double predicted = p.predicted_h_s[r], observed = p.observed_h_s[r];
      char line[200];
      if (p.limit == sim::StepLimit::always_stable) {
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
        const sim::BlowUpResult& run = p.runs[r][j];
        sweep_csv << name << ',' << rows[r].scale << ',' << format_e(h_s[j]) << ','
                  << format_e(predicted) << ',' << (run.stable ? 1 : 0) << ',' << run.steps_run
                  << ',' << format_e(run.max_growth) << '\n';
      }
    }
  }
  std::fputs(table.str().c_str(), stdout);
  write_text(options.out / "critical_steps.csv", critical_csv.str());
  write_text(options.out / "stability.csv", sweep_csv.str());
  write_text(options.out / "run.txt", "weft " + std::string(version()) +
                                          "\ncommand: " + options.command_line + "\n");
  write_heatmap(options.out / "stability.png", "weft stability: " + cloth_text, rows, panels,
                h_s, h_lo, h_hi);
  std::fprintf(stderr, "weft: wrote %s (stability.png, stability.csv, critical_steps.csv) in %s\n",
               options.out.c_str(), format_duration(progress.elapsed_s()).c_str());
  return 0;
}

}  // namespace weft::app
