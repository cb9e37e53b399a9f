#pragma once
// Tension-field fold generator for a vertically suspended membrane (seed 001: Conci 2007,
// "A model for the displacement behavior of after buckled membranes and textiles based on
// tension field theory and experiments", §5.2). From the fabric and its supports it finds the
// amplitude ratio Q of the wrinkle lines (eq. 7), their number n, their depth z_max (eq. 9)
// and the length L′ of the wrinkled upper boundary (eq. 8). No time stepping: a few
// evaluations of closed forms and one quadrature each. The geometry (wrinkle lines, the
// displaced grid) is in fold_geometry.h; docs/folds.md explains the model and its calibration.
//
// Three findings from reading the paper carefully (docs/folds.md has the numbers):
// - Span. §6 says "the support displacement is 10 cm, so l = 120 cm" (l = L − 2d), but Table 1
//   and the §6 example satisfy eq. (8) with l = L − d = 130 cm (L′ within 0.4 % of L for the
//   published n; with l = 120 cm every published n misses L by more than 6 %). weft uses
//   l = L − d: d is the total shortening of the span.
// - n. Iterating eq. (10) literally (step n up while L′ > L, down while L′ < L) cycles between
//   two values of n when neither meets the tolerance. L′ decreases strictly with n (eq. 9 gives
//   a smaller z_max for more wrinkles, and a_n = a0/Qⁿ shrinks), so n is found by a monotone
//   search that always terminates, and the n whose L′ is closest to L is kept.
// - c. Eq. (7) with a textbook plate-buckling constant (c = kπ²/12 ≈ 3.3 for k = 4) gives Q
//   much closer to 1 than Table 1's values. c is a parameter; its default is the value that best
//   reproduces Table 1's Q (a least-squares fit, calibrate_load_constant()).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace weft::sim {

// c of eq. (7) fitted to Table 1 of seed 001 (its three Q values) with ν = 0.3 and
// l = L − d: the least-squares fit is c ≈ 35.1 (Q residuals +0.068, −0.003, −0.129 for
// h = 90, 140, 235 cm; rms 0.084). One c cannot fit all three rows: eq. (7) makes Q fall as h
// grows, Table 1's Q does not (each row alone needs c ≈ 25.6, 35.7, 77.5).
inline constexpr double conci_table1_load_constant = 35.1;

// Inputs, SI units. The membrane hangs in a vertical plane from two point supports at its top
// corners, brought closer by d so that their span is l = L − d.
struct TensionFieldInputs {
  double height_m = 0.0;            // h: the membrane's height
  double width_m = 0.0;             // L: its initial (flat) width, the upper boundary's length
  double support_shift_m = 0.0;     // d: how much the supports were brought together; l = L − d
  double thickness_m = 0.0;         // t
  double youngs_modulus_Pa = 0.0;   // E
  double poisson_ratio = 0.3;       // ν, in (−1, 0.5]
  double weight_N_m2 = 0.0;         // w: weight per area (Conci's w = W/area), N/m²
  double load_constant = conci_table1_load_constant;  // c of eq. (7), > 0
  double tolerance = 0.05;          // on |L′ − L|/L; the paper uses 5 %
  std::optional<double> ratio;      // Q given (> 1) instead of eq. (7)'s

  double span_m() const { return width_m - support_shift_m; }  // l
};

// Bad input: `field` names the quantity ("h", "L", "d", "t", "E", "nu", "w", "c",
// "tolerance", "Q"), what() says what was expected and what was given.
class TensionFieldInputError : public std::invalid_argument {
 public:
  TensionFieldInputError(std::string field, const std::string& message)
      : std::invalid_argument(message), m_field(std::move(field)) {}
  const std::string& field() const { return m_field; }

 private:
  std::string m_field;
};

// Throws TensionFieldInputError unless every input is finite and in range: h, L, t, E, w, c > 0;
// 0 ≤ d < L (l > 0); −1 < ν ≤ 0.5; 0 < tolerance < 1; Q > 1 when given.
void validate(const TensionFieldInputs& inputs);

// σ_cr = c E t² / (l² (1 − ν²)), Pa: the critical compressive stress, right of eq. (7).
double critical_stress_Pa(const TensionFieldInputs& inputs);

// w h (Q − 1)² / (t Q (Q + 1)), Pa: the largest compressive stress for ratio Q, left of
// eq. (7). It grows with Q towards w h / t.
double compressive_stress_Pa(double weight_N_m2, double height_m, double thickness_m, double ratio);

// Q > 1 with compressive stress = σ_cr (eq. 7 at equality), in closed form: with
// R = σ_cr t / (w h), (1 − R) Q² − (2 + R) Q + 1 = 0, Q = (2 + R + √(R(R + 8))) / (2(1 − R)).
// None when R ≥ 1: the stress w h / t that Q → ∞ approaches stays below critical, the
// membrane does not wrinkle.
std::optional<double> ratio_from_critical_stress(const TensionFieldInputs& inputs);

// Amplitudes a_i = a0 / Q^i, i = 0..n (eq. 5): a geometric progression of ratio 1/Q.
std::vector<double> wrinkle_amplitudes_m(double a0_m, double ratio, int n);

// The largest n for which eq. (9) has a solution z_max ≥ 0: Σ (a_{i−1} − a_i) = a0 (1 − Q⁻ⁿ)
// must not exceed h, i.e. n ≤ log(a0 / (a0 − h)) / log Q — eq. (10) with a_n = a0 − h (the
// paper's a_n = 0.01 h for a0 = 1.01 h). Requires a0 > h and Q > 1; at least 1.
int max_wrinkle_count(double height_m, double a0_m, double ratio);

// z_max solving eq. (9), h = Σ_{i=1..n} √((a_{i−1} − a_i)² + (2 z_max)²), by bisection (the sum
// grows strictly with z_max); m. None when no z_max ≥ 0 solves it (n > max_wrinkle_count).
std::optional<double> z_max_from_inextensibility_m(double height_m, double a0_m, double ratio,
                                                  int n);

// L′ of eq. (8): the length of the cosine arc y = A cos(πx/l), x ∈ [−l/2, l/2], whose
// amplitude combines the upper line's a_n and z_max: A² = a_n² + z_max², by the composite
// Simpson rule on `intervals` (even, ≥ 2) intervals; m.
double boundary_length_m(double span_m, double amplitude_m, int intervals = 256);

enum class TensionFieldStatus {
  converged,          // |L′ − L| / L ≤ tolerance
  tolerance_not_met,  // the closest n still misses L by more than the tolerance
  no_wrinkling,       // eq. (7) has no Q: the stress stays below critical
};

struct TensionFieldResult {
  TensionFieldStatus status = TensionFieldStatus::no_wrinkling;
  double span_m = 0.0;                 // l = L − d
  double critical_stress_Pa = 0.0;     // σ_cr of eq. (7)
  double ratio = 0.0;                  // Q: given, or from eq. (7); 0 with no_wrinkling
  bool ratio_given = false;            // Q was an input, not eq. (7)'s
  int wrinkles = 0;                    // n
  std::vector<double> amplitudes_m;    // a_0 … a_n (a0 = 1.01 h), n + 1 values; empty without wrinkles
  double z_max_m = 0.0;                // eq. (9)
  double boundary_length_m = 0.0;      // L′, eq. (8); l without wrinkles
  double relative_error = 0.0;         // (L′ − L) / L, signed
  int evaluations = 0;                 // n values tried by the search
  std::string message;                 // one line for people: what was found, or why not

  bool converged() const { return status == TensionFieldStatus::converged; }
};

// Seed 001 §5.2: Q (eq. 7 or given), a0 = 1.01 h, then the n in [1, max_wrinkle_count] whose
// L′ (with z_max from eq. 9) is closest to L, found by bisection on the sign of L′(n) − L.
// Throws TensionFieldInputError for bad input (validate).
[[nodiscard]] TensionFieldResult solve_tension_field(const TensionFieldInputs& inputs);

// One published case for calibrating c: the inputs (their load_constant and ratio are ignored)
// and the Q the paper reports for them.
struct PublishedRatio {
  TensionFieldInputs inputs;
  double ratio = 0.0;
};

struct LoadConstantFit {
  double load_constant = 0.0;    // c minimising Σ (Q_eq7(c) − Q_published)²
  std::vector<double> residuals; // Q_eq7(c) − Q_published, per case
  double rms_residual = 0.0;
};

// Least-squares c for eq. (7) over the cases: a scan of log c over [1e-3, 1e6] then a
// golden-section refinement around the best scan point. A case that does not wrinkle at some c
// counts as Q = ∞ there. Throws std::invalid_argument for no cases.
LoadConstantFit calibrate_load_constant(const std::vector<PublishedRatio>& cases);

// Seed 001 Table 1 (L = 140 cm, d = 10 cm, t = 0.25 mm, E = 165 MPa, w = 15e-7 N/mm², ν = 0.3
// assumed; h = 90, 140, 235 cm) with its published Q = 1.31, 1.29, 1.34.
std::vector<PublishedRatio> conci_table1_ratios();

}  // namespace weft::sim
