// Seed 001 §5.2: the ratio Q, number n, depth z_max and boundary length L′ of the wrinkles of a
// vertically suspended membrane (tension_field.h).

#include "sim/folds/tension_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "base/check.h"
#include "base/format.h"
#include "base/constants.h"

namespace weft::sim {

namespace {

// a0 = 1.01 h: the paper's first approximation of the lowest wrinkle line's amplitude (§5.2).
constexpr double kLowestAmplitudeFactor = 1.01;

// unit: the SI unit the value is in, "" for a pure number.
void require(bool ok, const char* field, const std::string& expected, double value,
             const char* unit = "") {
  if (!ok)
    throw TensionFieldInputError(field, std::string(field) + ": expected " + expected + ", got " +
                                            base::format("%.6g", value) + (*unit ? " " : "") + unit);
}

void require_positive(const char* field, const char* what, double value, const char* unit) {
  require(std::isfinite(value) && value > 0.0, field,
          std::string("the ") + what + " as a finite number > 0", value, unit);
}

// L′(n) for ratio Q: z_max from eq. (9), then eq. (8). None when eq. (9) has no solution.
struct Trial {
  double z_max_m = 0.0;
  double length_m = 0.0;
};

std::optional<Trial> trial(const TensionFieldInputs& in, double a0, double ratio, int n) {
  const std::optional<double> z = z_max_from_inextensibility_m(in.height_m, a0, ratio, n);
  if (!z) return std::nullopt;
  const double a_n = a0 / std::pow(ratio, n);
  return Trial{*z, boundary_length_m(in.span_m(), std::hypot(a_n, *z))};
}

}  // namespace

void validate(const TensionFieldInputs& in) {
  require_positive("h", "height", in.height_m, "m");
  require_positive("L", "width", in.width_m, "m");
  require(std::isfinite(in.support_shift_m) && in.support_shift_m >= 0.0, "d",
          "the support displacement as a finite number >= 0", in.support_shift_m, "m");
  require(in.support_shift_m < in.width_m, "d",
          "a support displacement smaller than the width L = " + base::format("%.6g", in.width_m) +
              " m (the span l = L - d must be > 0)",
          in.support_shift_m, "m");
  require_positive("t", "thickness", in.thickness_m, "m");
  require_positive("E", "Young's modulus", in.youngs_modulus_Pa, "Pa");
  require(std::isfinite(in.poisson_ratio) && in.poisson_ratio > -1.0 && in.poisson_ratio <= 0.5,
          "nu", "Poisson's ratio in (-1, 0.5]", in.poisson_ratio);
  require_positive("w", "weight per area", in.weight_N_m2, "N/m^2");
  require_positive("c", "load-condition constant", in.load_constant, "");
  require(std::isfinite(in.tolerance) && in.tolerance > 0.0 && in.tolerance < 1.0, "tolerance",
          "a relative tolerance in (0, 1)", in.tolerance);
  if (in.ratio)
    require(std::isfinite(*in.ratio) && *in.ratio > 1.0, "Q",
            "an amplitude ratio > 1 (a_{i-1}/a_i, eq. 5)", *in.ratio);
}

double critical_stress_Pa(const TensionFieldInputs& in) {
  const double l = in.span_m();
  return in.load_constant * in.youngs_modulus_Pa * in.thickness_m * in.thickness_m /
         (l * l * (1.0 - in.poisson_ratio * in.poisson_ratio));
}

double compressive_stress_Pa(double weight_N_m2, double height_m, double thickness_m,
                             double ratio) {
  return weight_N_m2 * height_m * (ratio - 1.0) * (ratio - 1.0) /
         (thickness_m * ratio * (ratio + 1.0));
}

std::optional<double> ratio_from_critical_stress(const TensionFieldInputs& in) {
  const double r = critical_stress_Pa(in) * in.thickness_m / (in.weight_N_m2 * in.height_m);
  if (!(r < 1.0)) return std::nullopt;
  return (2.0 + r + std::sqrt(r * (r + 8.0))) / (2.0 * (1.0 - r));
}

std::vector<double> wrinkle_amplitudes_m(double a0_m, double ratio, int n) {
  std::vector<double> a(static_cast<std::size_t>(std::max(n, 0)) + 1);
  for (int i = 0; i <= n; ++i) a[static_cast<std::size_t>(i)] = a0_m / std::pow(ratio, i);
  return a;
}

int max_wrinkle_count(double height_m, double a0_m, double ratio) {
  const double bound = std::log(a0_m / (a0_m - height_m)) / std::log(ratio);
  int n = std::max(1, static_cast<int>(std::floor(bound)));
  // Guard the floor against rounding: the vertical drops must fit in h.
  while (n > 1 && a0_m * (1.0 - std::pow(ratio, -n)) > height_m) --n;
  return n;
}

std::optional<double> z_max_from_inextensibility_m(double height_m, double a0_m, double ratio,
                                                  int n) {
  const std::vector<double> a = wrinkle_amplitudes_m(a0_m, ratio, n);
  const auto fibre_length = [&](double z) {
    double sum = 0.0;
    for (int i = 1; i <= n; ++i) sum += std::hypot(a[i - 1] - a[i], 2.0 * z);
    return sum;
  };
  if (fibre_length(0.0) > height_m) return std::nullopt;
  // Every term is at least 2z, so z_max ≤ h / (2n).
  double lo = 0.0, hi = height_m / (2.0 * n);
  for (int k = 0; k < 200 && hi - lo > 1e-15 * height_m; ++k) {
    const double mid = 0.5 * (lo + hi);
    (fibre_length(mid) > height_m ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

double boundary_length_m(double span_m, double amplitude_m, int intervals) {
  if (intervals < 2 || intervals % 2 != 0)
    throw std::invalid_argument("boundary_length_m: Simpson's rule needs an even number >= 2 of "
                                "intervals, got " + std::to_string(intervals));
  const double k = base::kPi * amplitude_m / span_m;  // slope scale of A cos(πx/l)
  const auto integrand = [&](double x) {
    const double s = std::sin(base::kPi * x / span_m);
    return std::sqrt(1.0 + k * k * s * s);
  };
  const double step = span_m / intervals;
  double sum = integrand(-0.5 * span_m) + integrand(0.5 * span_m);
  for (int j = 1; j < intervals; ++j) sum += (j % 2 ? 4.0 : 2.0) * integrand(-0.5 * span_m + j * step);
  return sum * step / 3.0;
}

TensionFieldResult solve_tension_field(const TensionFieldInputs& in) {
  validate(in);
  TensionFieldResult r;
  r.span_m = in.span_m();
  r.critical_stress_Pa = critical_stress_Pa(in);
  r.boundary_length_m = r.span_m;
  r.relative_error = (r.span_m - in.width_m) / in.width_m;
  r.ratio_given = in.ratio.has_value();
  const std::optional<double> ratio = in.ratio ? in.ratio : ratio_from_critical_stress(in);
  if (!ratio) {
    r.status = TensionFieldStatus::no_wrinkling;
    r.message = "no wrinkling: the compressive stress w h (Q-1)^2/(t Q (Q+1)) < w h / t = " +
                base::format("%.6g", in.weight_N_m2 * in.height_m / in.thickness_m) +
                " Pa stays below the critical stress " + base::format("%.6g", r.critical_stress_Pa) +
                " Pa of eq. (7) for every Q";
    return r;
  }
  r.ratio = *ratio;
  const double a0 = kLowestAmplitudeFactor * in.height_m;
  const int n_max = max_wrinkle_count(in.height_m, a0, r.ratio);

  // L′(n) decreases strictly with n: find the first n with L′(n) ≤ L by bisection on
  // [1, n_max], then keep it or n − 1, whichever is closer to L.
  const auto evaluate = [&](int n) {
    ++r.evaluations;
    const std::optional<Trial> t = trial(in, a0, r.ratio, n);
    // n ≤ n_max always has a solution; a failure here is a bug, not bad input.
    WEFT_CHECK(t.has_value(), "solve_tension_field: eq. (9) unsolvable for n <= n_max");
    return *t;
  };
  int lo = 1, hi = n_max;  // invariant: L′(n) > L for n < lo; L′(hi) ≤ L, or hi = n_max
  Trial at_hi = evaluate(hi);
  if (at_hi.length_m <= in.width_m) {
    while (lo < hi) {
      const int mid = lo + (hi - lo) / 2;
      const Trial t = evaluate(mid);
      if (t.length_m <= in.width_m) {
        hi = mid;
        at_hi = t;
      } else {
        lo = mid + 1;
      }
    }
  }
  int n = hi;
  Trial best = at_hi;
  if (n > 1) {
    const Trial below = evaluate(n - 1);
    if (std::abs(below.length_m - in.width_m) < std::abs(best.length_m - in.width_m)) {
      n -= 1;
      best = below;
    }
  }
  r.wrinkles = n;
  r.amplitudes_m = wrinkle_amplitudes_m(a0, r.ratio, n);
  r.z_max_m = best.z_max_m;
  r.boundary_length_m = best.length_m;
  r.relative_error = (best.length_m - in.width_m) / in.width_m;
  const bool met = std::abs(r.relative_error) <= in.tolerance;
  r.status = met ? TensionFieldStatus::converged : TensionFieldStatus::tolerance_not_met;
  char percent[32];
  std::snprintf(percent, sizeof percent, "%+.2f %%", 100.0 * r.relative_error);
  const std::string miss = std::string(percent) + " from L";
  if (met)
    r.message = "converged: L' is " + miss + " (tolerance " + base::format("%.6g", 100.0 * in.tolerance) + " %)";
  else
    r.message = "tolerance not met: the closest n = " + std::to_string(n) + " (of 1.." +
                std::to_string(n_max) + ") gives L' " + miss + ", more than the tolerance " +
                base::format("%.6g", 100.0 * in.tolerance) + " %";
  return r;
}

LoadConstantFit calibrate_load_constant(const std::vector<PublishedRatio>& cases) {
  if (cases.empty()) throw std::invalid_argument("calibrate_load_constant: no cases");
  const auto ratio_at = [](const PublishedRatio& p, double c) {
    TensionFieldInputs in = p.inputs;
    in.load_constant = c;
    in.ratio.reset();
    return ratio_from_critical_stress(in).value_or(std::numeric_limits<double>::infinity());
  };
  const auto cost = [&](double log_c) {
    double sum = 0.0;
    for (const PublishedRatio& p : cases) {
      const double e = ratio_at(p, std::exp(log_c)) - p.ratio;
      sum += e * e;
    }
    return sum;
  };
  // Scan: 100 points per decade over [1e-3, 1e6].
  const double first = std::log(1e-3), last = std::log(1e6);
  const int points = 900;
  const double step = (last - first) / points;
  int best = 0;
  double best_cost = cost(first);
  for (int k = 1; k <= points; ++k) {
    const double c = cost(first + k * step);
    if (c < best_cost) {
      best_cost = c;
      best = k;
    }
  }
  // Golden section on the bracket around the best scan point.
  double a = first + std::max(best - 1, 0) * step, b = first + std::min(best + 1, points) * step;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = cost(x1), f2 = cost(x2);
  for (int k = 0; k < 200 && b - a > 1e-12; ++k) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = cost(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = cost(x2);
    }
  }
  LoadConstantFit fit;
  fit.load_constant = std::exp(0.5 * (a + b));
  double sum = 0.0;
  for (const PublishedRatio& p : cases) {
    fit.residuals.push_back(ratio_at(p, fit.load_constant) - p.ratio);
    sum += fit.residuals.back() * fit.residuals.back();
  }
  fit.rms_residual = std::sqrt(sum / static_cast<double>(cases.size()));
  return fit;
}

std::vector<PublishedRatio> conci_table1_ratios() {
  std::vector<PublishedRatio> cases;
  const std::pair<double, double> rows[] = {{90.0, 1.31}, {140.0, 1.29}, {235.0, 1.34}};
  for (const auto& [h_cm, q] : rows) {
    PublishedRatio p;
    p.inputs.height_m = 1e-2 * h_cm;
    p.inputs.width_m = 1.40;
    p.inputs.support_shift_m = 0.10;
    p.inputs.thickness_m = 0.25e-3;
    p.inputs.youngs_modulus_Pa = 165e6;
    p.inputs.poisson_ratio = 0.3;
    p.inputs.weight_N_m2 = 15e-7 * 1e6;  // N/mm² → N/m²
    p.ratio = q;
    cases.push_back(p);
  }
  return cases;
}

}  // namespace weft::sim
