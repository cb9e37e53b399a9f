#pragma once
// The optimisation of `weft fit`: NLopt's derivative-free BOBYQA (Powell
// 2009) or Nelder–Mead on log10 of the parameters, within their bounds, each evaluation a
// settle to rest (fit_problem.h); then the objective profile along each parameter around the
// optimum and the sensitivity band it gives.

#include <functional>
#include <string>
#include <vector>

#include "app/fit/fit_problem.h"

namespace weft::app {

// The objective along one parameter, the others at their optimum: `points` values on each
// side of the optimum out to ×/÷ (1 + span), equally spaced in log.
struct Profile {
  std::vector<double> values;     // SI, increasing; the optimum among them
  std::vector<double> objective;
};

struct FittedParameter {
  double value = 0.0;             // at the optimum, SI
  // The sensitivity band: the interval around the value where the profile stays ≤ optimum +
  // band (linear interpolation between profile points). *_open: the profile never rose that
  // far on that side, so the band reaches at least to the profile's end (or a bound).
  double band_low = 0.0, band_high = 0.0;
  bool low_open = false, high_open = false;
};

struct FitResult {
  std::vector<Evaluation> evaluations;  // the optimiser's, in order
  std::vector<Evaluation> profile_evaluations;
  Evaluation best;
  std::vector<Profile> profiles;        // one per parameter (empty with profile.points = 0)
  std::vector<FittedParameter> fitted;  // one per parameter; without a profile the band is
                                        // the value itself, open on both sides
  double band = 0.0;                    // the objective rise that bounds the band
  std::string stop_reason;              // NLopt's, e.g. "x tolerance reached"
};

// Phase of an evaluation, for progress lines and the CSV log.
enum class FitPhase { optimise, profile };

// Why an NLopt optimisation stopped (`result`: an nlopt::result), in words for the reports.
std::string nlopt_stop_reason(int result);

// Fits; `on_evaluation` sees each evaluation as it is made (its 1-based number and phase).
FitResult run_fit(FitProblem& problem,
                  const std::function<void(const Evaluation&, int, FitPhase)>& on_evaluation = {});

// The band of one profile around its optimum (index `best` of the profile).
FittedParameter sensitivity_band(const Profile& profile, std::size_t best, double band);

}  // namespace weft::app
