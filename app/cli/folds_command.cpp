// weft folds: solve the tension field (sim/folds/tension_field.h), print it, render the folded
// membrane and draw the wrinkle lines on a photo (folds_overlay.h).

#include "app/cli/folds_command.h"

#include <CLI/CLI.hpp>
#include <memory>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/io/finite_outputs.h"
#include "app/report/folds_overlay.h"
#include "app/run/frame_mesh.h"
#include "app/scene/json_reader.h"
#include "app/cli/options.h"
#include "app/run/renderer_choice.h"
#include "app/scene/scene.h"
#include "app/scene/units.h"

namespace weft::app {

namespace {

namespace fs = std::filesystem;

const char* status_name(sim::TensionFieldStatus s) {
  switch (s) {
    case sim::TensionFieldStatus::converged: return "converged";
    case sim::TensionFieldStatus::tolerance_not_met: return "tolerance_not_met";
    case sim::TensionFieldStatus::no_wrinkling: return "no_wrinkling";
  }
  return "?";
}

void print_text(const sim::TensionFieldInputs& in, const sim::TensionFieldResult& r) {
  std::printf("weft folds: h = %g cm, L = %g cm, d = %g cm (span l = %g cm), t = %g mm, "
              "E = %g MPa, w = %g N/mm^2, nu = %g, c = %g\n",
              1e2 * in.height_m, 1e2 * in.width_m, 1e2 * in.support_shift_m, 1e2 * r.span_m,
              1e3 * in.thickness_m, 1e-6 * in.youngs_modulus_Pa, 1e-6 * in.weight_N_m2,
              in.poisson_ratio, in.load_constant);
  std::printf("  sigma_cr  %.4g Pa (eq. 7)\n", r.critical_stress_Pa);
  if (r.status == sim::TensionFieldStatus::no_wrinkling) {
    std::printf("  status    %s\n", r.message.c_str());
    return;
  }
  std::printf("  Q         %.4g (%s)\n", r.ratio, r.ratio_given ? "given" : "eq. 7 at equality");
  std::printf("  n         %d\n", r.wrinkles);
  std::printf("  z_max     %.3g cm\n", 1e2 * r.z_max_m);
  std::string amplitudes;
  for (double a : r.amplitudes_m) {
    char cm[32];
    std::snprintf(cm, sizeof cm, "%s%.4g", amplitudes.empty() ? "" : ", ", 1e2 * a);
    amplitudes += cm;
  }
  std::printf("  a_i       %s cm (i = 0..%d)\n", amplitudes.c_str(), r.wrinkles);
  std::printf("  L'        %.4g cm (%+.2f %% from L)\n", 1e2 * r.boundary_length_m,
              1e2 * r.relative_error);
  std::printf("  status    %s\n", r.message.c_str());
}

// A camera on the −y side (where positive folds bulge), a little to the right and above,
// framing the membrane hanging from top_center.
render::RenderSettings membrane_render_settings(const sim::FoldPattern& p, const sim::Vec3& top,
                                                int width, int height) {
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  const double extent = std::max(1.1 * p.height_m, 0.75 * p.span_m * height / width * 1.6);
  const Eigen::Vector3d target(top.x(), top.y(), top.z() - 0.55 * p.height_m);
  const double distance = 1.9 * extent;
  s.camera.target = target;
  s.camera.eye = target + Eigen::Vector3d(0.35 * distance, -distance, 0.12 * distance);
  s.camera.far_m = 10.0 * distance;
  s.light_direction = {0.7, -0.5, 0.6};  // grazing from the right: the folds cast shade
  return s;
}

}  // namespace

std::string folds_flag(const std::string& field) {
  if (field == "h") return "--h/--h-cm";
  if (field == "L") return "--L/--L-cm";
  if (field == "d") return "--d/--d-cm";
  if (field == "t") return "--t/--t-mm";
  if (field == "E") return "--E/--E-MPa";
  if (field == "w") return "--w/--w-N-mm2";
  return "--" + field;  // --nu, --c, --Q, --tolerance
}

nlohmann::json folds_json(const sim::TensionFieldInputs& in, const sim::TensionFieldResult& r) {
  nlohmann::json j;
  j["inputs"] = {{"height_m", in.height_m},
                 {"width_m", in.width_m},
                 {"support_shift_m", in.support_shift_m},
                 {"thickness_m", in.thickness_m},
                 {"youngs_modulus_Pa", in.youngs_modulus_Pa},
                 {"poisson_ratio", in.poisson_ratio},
                 {"weight_N_m2", in.weight_N_m2},
                 {"load_constant", in.load_constant},
                 {"tolerance", in.tolerance}};
  j["span_m"] = r.span_m;
  j["critical_stress_Pa"] = r.critical_stress_Pa;
  j["Q"] = r.status == sim::TensionFieldStatus::no_wrinkling ? nlohmann::json() : nlohmann::json(r.ratio);
  j["Q_given"] = r.ratio_given;
  j["n"] = r.wrinkles;
  j["z_max_m"] = r.z_max_m;
  j["amplitudes_m"] = r.amplitudes_m;
  j["boundary_length_m"] = r.boundary_length_m;
  j["relative_error"] = r.relative_error;
  j["status"] = status_name(r.status);
  j["converged"] = r.converged();
  j["message"] = r.message;
  return j;
}

FoldedMembrane folded_membrane(const sim::FoldPattern& p, sim::MembraneShape shape,
                               const sim::Vec3& top_center_m) {
  // About 1 cm cells, at most 240 vertices a side: the top strips of a curtain are a few cm.
  const double cell = std::max(0.01, std::max(p.width_m, p.height_m) / 239.0);
  sim::GridSpec spec;
  spec.size_u_m = p.width_m;
  spec.size_v_m = p.height_m;
  spec.nu = std::max<sim::Index>(2, static_cast<sim::Index>(std::lround(p.width_m / cell)) + 1);
  spec.nv = std::max<sim::Index>(2, static_cast<sim::Index>(std::lround(p.height_m / cell)) + 1);
  spec.origin = top_center_m - sim::Vec3(0.5 * p.width_m, 0.0, 0.0);
  spec.warp_axis = sim::Vec3(1.0, 0.0, 0.0);   // across
  spec.weft_axis = sim::Vec3(0.0, 0.0, -1.0);  // down
  FoldedMembrane m{sim::make_grid(spec), {}};
  m.x = sim::fold_rest_positions(p, m.mesh.rest_positions, top_center_m, shape);
  return m;
}

int run_folds(const FoldsOptions& options) {
  const sim::TensionFieldInputs& in = options.inputs;
  sim::TensionFieldResult result;
  try {
    result = sim::solve_tension_field(in);
  } catch (const sim::TensionFieldInputError& e) {
    throw InputError(folds_flag(e.field()) + ": " + e.what());
  }
  // Inputs each in range can still combine beyond what doubles hold (h ≫ L): say so, not nan.
  if (!std::isfinite(result.boundary_length_m) || !std::isfinite(result.z_max_m) ||
      !std::isfinite(result.relative_error))
    throw InputError("--h, --L, --d: these proportions (h/l = " +
                     std::to_string(in.height_m / in.span_m()) +
                     ") give a non-finite L' or z_max; the model needs h and l of similar sizes");
  const sim::FoldPattern pattern = sim::make_fold_pattern(in, result, options.interpolation);

  // Check everything the outputs need before writing anything.
  std::optional<render::Image> photo;
  std::optional<OverlayMapping> mapping;
  if (options.overlay) {
    if (!options.supports)
      throw InputError("--overlay needs --supports x1,y1,x2,y2: the supports' pixels in the photo");
    if (!fs::is_regular_file(*options.overlay))
      throw InputError("--overlay: " + options.overlay->string() + ": no such file");
    try {
      photo = render::read_image(*options.overlay);
    } catch (const std::exception& e) {
      throw InputError(std::string("--overlay: ") + e.what());
    }
    OverlayPlacement placement = parse_supports(*options.supports);
    placement.bottom_px = options.bottom_px;
    mapping = overlay_mapping(pattern, placement, photo->width(), photo->height());
  } else if (options.supports || options.bottom_px) {
    throw InputError("--supports and --bottom place the photo of --overlay PHOTO, which is missing");
  }
  int width = 640, height = 480;
  if (options.size) std::tie(width, height) = parse_size(*options.size, "--size");

  if (options.json)
    std::printf("%s\n", finite_json_text(folds_json(in, result), "weft folds' result").c_str());
  else
    print_text(in, result);

  const fs::path dir = options.out.value_or(fs::path("out") / "folds");
  if (options.out) {
    const sim::Vec3 top(0.0, 0.0, 1.1 * in.height_m + 0.1);
    const FoldedMembrane m = folded_membrane(pattern, options.shape, top);
    render::RenderSettings settings = membrane_render_settings(pattern, top, width, height);
    const std::unique_ptr<render::Renderer> renderer = make_chosen_renderer(settings);
    fs::create_directories(dir);
    render::write_png(renderer->render(to_render_mesh(m.mesh, m.x), settings, {}),
                      dir / "folds.png");
    std::fprintf(stderr, "weft: wrote %s\n", (dir / "folds.png").c_str());
  }
  if (photo) {
    fs::create_directories(dir);
    render::write_png(draw_fold_overlay(std::move(*photo), pattern, *mapping),
                      dir / "folds_overlay.png");
    std::fprintf(stderr, "weft: wrote %s\n", (dir / "folds_overlay.png").c_str());
  }
  return exit_ok;
}

namespace {

// An input of the model, given either as a quantity with its unit like a scene file's
// (--t "0.25 mm", --E "2.5 GPa") or as a number in the paper's unit (--t-mm 0.25); held in SI.
struct FoldsInput {
  const char* field;     // "t": the flag --t and TensionFieldInputError::field
  const char* unit_flag;  // "--t-mm": the paper-unit flag
  double unit_factor;    // its unit in SI (1e-3 for mm)
  Quantity kind;         // what --t accepts
  Range range_si;        // bounds a person could mean, SI
  const char* what;      // "Thickness t"
  std::optional<double> si;
};

// The flags as typed, converted to SI when the command runs.
struct FoldsFlags {
  // Bounds a person could mean (a cloth up to 100 m, a sheet up to 10 cm thick); the model
  // itself checks how they combine (sim/folds/tension_field.h).
  FoldsInput h{"h", "--h-cm", 1e-2, Quantity::length, Range::gt(0.0).le(100.0),
               "Height h of the cloth", {}};
  FoldsInput L{"L", "--L-cm", 1e-2, Quantity::length, Range::gt(0.0).le(100.0),
               "Width L of the flat cloth", {}};
  FoldsInput d{"d", "--d-cm", 1e-2, Quantity::length, Range::closed(0.0, 100.0),
               "Support displacement d (the span is l = L - d)", {}};
  FoldsInput t{"t", "--t-mm", 1e-3, Quantity::length, Range::gt(0.0).le(0.1), "Thickness t", {}};
  FoldsInput E{"E", "--E-MPa", 1e6, Quantity::stress, Range::gt(0.0).le(1e12),
               "Young's modulus E", {}};
  FoldsInput w{"w", "--w-N-mm2", 1e6, Quantity::stress, Range::gt(0.0).le(1e6),
               "Weight per area w", {}};
  std::optional<double> Q;
  std::string shape = "rectangle", interpolation = "cosine";
};

double required_si(const FoldsInput& in) {
  if (!in.si)
    throw InputError(std::string("--") + in.field + " (or " + in.unit_flag + ") is required: " +
                     in.what + ", e.g. --" + in.field + " \"" +
                     (in.kind == Quantity::length ? "25 cm" : "2.5 MPa") + "\"");
  return *in.si;
}

FoldsOptions folds_options(FoldsOptions o, const FoldsFlags& f) {
  o.inputs.height_m = required_si(f.h);
  o.inputs.width_m = required_si(f.L);
  o.inputs.support_shift_m = required_si(f.d);
  o.inputs.thickness_m = required_si(f.t);
  o.inputs.youngs_modulus_Pa = required_si(f.E);
  o.inputs.weight_N_m2 = required_si(f.w);
  if (f.Q) o.inputs.ratio = *f.Q;
  o.shape = f.shape == "cosine" ? sim::MembraneShape::cosine : sim::MembraneShape::rectangle;
  o.interpolation = f.interpolation == "linear" ? sim::FoldInterpolation::linear
                                                : sim::FoldInterpolation::cosine;
  return o;
}

// --X "QUANTITY" and --X-UNIT NUMBER for one input; at most one of them.
void add_input_flag(CLI::App& cmd, FoldsInput& in) {
  const std::string flag = std::string("--") + in.field;
  const std::string si_unit = si_unit_symbol(in.kind);
  CLI::Option* quantity = cmd.add_option_function<std::string>(
      flag,
      [&in, flag, si_unit](const std::string& text) {
        double value = 0.0;
        try {
          value = parse_quantity(text, in.kind);
        } catch (const UnitError& e) {
          throw InputError(flag + ": " + e.what());
        }
        if (!in.range_si.contains(value))
          throw InputError(flag + ": expected a value " + in.range_si.text() + " " + si_unit +
                           ", got '" + text + "'");
        in.si = value;
      },
      std::string(in.what) + " with its unit, like a scene file's value (e.g. " +
          (in.kind == Quantity::length ? "\"25 cm\"" : "\"2.5 MPa\"") + ")");
  Range paper = in.range_si;
  paper.min /= in.unit_factor;
  paper.max /= in.unit_factor;
  const std::string paper_unit = std::string(in.unit_flag).substr(std::string(in.field).size() + 3);
  CLI::Option* number = check_range(
      cmd.add_option_function<double>(
          in.unit_flag, [&in](const double& v) { in.si = v * in.unit_factor; },
          std::string(in.what) + ", in " + paper_unit + " (the paper's unit; or " + flag + ")"),
      paper);
  quantity->excludes(number);
}

// The inputs' flags.
void add_input_flags(CLI::App& cmd, FoldsFlags& f, FoldsOptions& o) {
  for (FoldsInput* in : {&f.h, &f.L, &f.d, &f.t, &f.E, &f.w}) add_input_flag(cmd, *in);
  check_range(cmd.add_option("--nu", o.inputs.poisson_ratio, "Poisson's ratio (default 0.3)"),
              Range::gt(-1.0).le(0.5));
  check_range(cmd.add_option("--c", o.inputs.load_constant,
                             "Load-condition constant c of eq. (7) (default: the fit to the "
                             "paper's Table 1)"),
              Range::gt(0.0).le(1e6));
  check_range(cmd.add_option("--Q", f.Q, "Amplitude ratio Q > 1, instead of eq. (7)'s"),
              Range::gt(1.0).le(1e6));
  check_range(cmd.add_option("--tolerance", o.inputs.tolerance, "On |L' - L|/L (default 0.05)"),
              Range::gt(0.0).lt(1.0));
}

}  // namespace

Command register_folds(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<FoldsOptions>();
  const auto f = std::make_shared<FoldsFlags>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "folds", "Tension-field folds of a cloth hanging from two supports (Conci 2007): print n, Q, "
               "z_max, a_i, L'; render them; draw them on a photo (docs/folds.md)");
  add_input_flags(*cmd, *f, *o);
  cmd->add_flag("--json", o->json, "Print the result as one JSON object");
  cmd->add_option("--out", o->out, "Render the folded cloth to DIR/folds.png (the overlay goes there too; default out/folds)");
  cmd->add_option("--size", o->size, "Image size WIDTHxHEIGHT of folds.png (default 640x480)");
  cmd->add_option("--shape", f->shape, "Membrane rendered: rectangle or cosine")
      ->check(CLI::IsMember({"rectangle", "cosine"}));
  cmd->add_option("--interpolation", f->interpolation,
                  "z between wrinkle lines: cosine (smooth) or linear (the paper's)")
      ->check(CLI::IsMember({"cosine", "linear"}));
  cmd->add_option("--overlay", o->overlay, "Photo (PNG/JPG) to draw the fold lines on: writes folds_overlay.png");
  cmd->add_option("--supports", o->supports, "x1,y1,x2,y2: the supports' pixels in the photo");
  check_range(cmd->add_option("--bottom", o->bottom_px,
                              "Pixel row of the cloth's bottom at the middle (default: same scale "
                              "as across)"),
              Range::closed(0.0, 1e5));
  return {cmd, [o, f] { return run_folds(folds_options(*o, *f)); }};
}

}  // namespace weft::app
