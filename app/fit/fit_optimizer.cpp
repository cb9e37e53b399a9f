// The optimisation of `weft fit` (see fit_optimizer.h).

#include "app/fit/fit_optimizer.h"

#include <algorithm>
#include <cmath>
#include <nlopt.hpp>

namespace weft::app {
namespace {

std::vector<double> from_log(const std::vector<double>& x) {
  std::vector<double> v;
  for (const double xi : x) v.push_back(std::pow(10.0, xi));
  return v;
}

// Where the profile crosses `level` between points i (below) and j (above), linear in log.
double crossing(const Profile& p, std::size_t i, std::size_t j, double level) {
  const double fi = p.objective[i], fj = p.objective[j];
  const double t = fj > fi ? (level - fi) / (fj - fi) : 0.0;
  const double li = std::log10(p.values[i]), lj = std::log10(p.values[j]);
  return std::pow(10.0, li + t * (lj - li));
}

}  // namespace

std::string nlopt_stop_reason(int result) {
  switch (static_cast<nlopt::result>(result)) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "objective stop value reached";
    case nlopt::FTOL_REACHED: return "objective tolerance reached";
    case nlopt::XTOL_REACHED: return "parameter tolerance reached";
    case nlopt::MAXEVAL_REACHED: return "max_evaluations reached";
    case nlopt::MAXTIME_REACHED: return "time limit reached";
    default: return "stopped (NLopt code " + std::to_string(result) + ")";
  }
}

FittedParameter sensitivity_band(const Profile& p, std::size_t best, double band) {
  FittedParameter f;
  f.value = p.values[best];
  const double level = p.objective[best] + band;
  f.band_low = p.values.front();
  f.low_open = true;
  for (std::size_t k = best; k-- > 0;)
    if (p.objective[k] > level) {
      f.band_low = crossing(p, k + 1, k, level);
      f.low_open = false;
      break;
    }
  f.band_high = p.values.back();
  f.high_open = true;
  for (std::size_t k = best + 1; k < p.values.size(); ++k)
    if (p.objective[k] > level) {
      f.band_high = crossing(p, k - 1, k, level);
      f.high_open = false;
      break;
    }
  return f;
}

namespace {

constexpr int kRestarts = 3;  // optimiser restarts from a profile point below the optimum

// NLopt's BOBYQA or Nelder–Mead on log10 of the parameters from x (moved to the optimum);
// returns why it stopped.
std::string optimise(const FitSpec& spec, std::vector<double>& x,
                     const std::function<double(const std::vector<double>&)>& evaluate) {
  const auto n = static_cast<unsigned>(spec.parameters.size());
  nlopt::opt opt(spec.optimizer.method == FitMethod::bobyqa ? nlopt::LN_BOBYQA : nlopt::LN_NELDERMEAD, n);
  std::vector<double> lo, hi;
  for (const FitParameter& p : spec.parameters) {
    lo.push_back(std::log10(p.min));
    hi.push_back(std::log10(p.max));
  }
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_maxeval(spec.optimizer.max_evaluations);
  opt.set_xtol_abs(spec.optimizer.x_tolerance);
  opt.set_initial_step(spec.optimizer.initial_step);
  using Callback = std::function<double(const std::vector<double>&)>;
  Callback callback = [&](const std::vector<double>& xs) { return evaluate(from_log(xs)); };
  opt.set_min_objective(
      [](const std::vector<double>& xs, std::vector<double>&, void* data) {
        return (*static_cast<Callback*>(data))(xs);
      },
      &callback);
  double minimum = 0.0;
  return nlopt_stop_reason(opt.optimize(x, minimum));
}

// The profile along parameter i around result.best (its band, FitResult::profiles).
Profile profile_parameter(const FitSpec& spec, std::size_t i, const Evaluation& best,
                          const std::function<double(const std::vector<double>&)>& evaluate) {
  Profile p;
  const FitParameter& param = spec.parameters[i];
  for (int k = -spec.profile.points; k <= spec.profile.points; ++k) {
    std::vector<double> v = best.values;
    v[i] = std::clamp(best.values[i] * std::pow(1.0 + spec.profile.span,
                                                static_cast<double>(k) / std::max(1, spec.profile.points)),
                      param.min, param.max);
    if (k != 0 && v[i] == best.values[i]) continue;  // clamped onto the optimum by a bound
    p.values.push_back(v[i]);
    p.objective.push_back(k == 0 ? best.objective : evaluate(v));
  }
  return p;
}

}  // namespace

FitResult run_fit(FitProblem& problem,
                  const std::function<void(const Evaluation&, int, FitPhase)>& on_evaluation) {
  const FitSpec& spec = problem.spec();
  const auto n = static_cast<unsigned>(spec.parameters.size());
  FitResult result;
  int count = 0;
  const Evaluation* best_profiled = nullptr;  // a profile point below the optimum, if any
  const auto evaluate = [&](const std::vector<double>& values, FitPhase phase) {
    Evaluation e = problem.evaluate(values);
    if (on_evaluation) on_evaluation(e, ++count, phase);
    (phase == FitPhase::optimise ? result.evaluations : result.profile_evaluations).push_back(e);
    if (phase == FitPhase::optimise &&
        (result.evaluations.size() == 1 || e.objective < result.best.objective))
      result.best = e;
    return e.objective;
  };
  std::vector<double> x;
  for (const FitParameter& p : spec.parameters) x.push_back(std::log10(p.start));
  result.band = spec.profile.band.value_or(default_band(spec.target));
  // A drape's objective is rough (its node pattern changes with the parameters): when the
  // profile finds a point below the optimum, the optimiser starts again from there.
  for (int start = 0; start <= kRestarts; ++start) {
    result.stop_reason = optimise(spec, x, [&](const std::vector<double>& values) {
      return evaluate(values, FitPhase::optimise);
    });
    result.fitted.clear();
    result.profiles.clear();
    const std::size_t profiled = result.profile_evaluations.size();
    const Evaluation best = result.best;
    for (std::size_t i = 0; i < n; ++i) {
      if (spec.profile.points == 0) {  // no profile: no band
        result.fitted.push_back({best.values[i], best.values[i], best.values[i], true, true});
        continue;
      }
      Profile p = profile_parameter(spec, i, best, [&](const std::vector<double>& v) {
        return evaluate(v, FitPhase::profile);
      });
      const std::size_t at = static_cast<std::size_t>(
          std::find(p.values.begin(), p.values.end(), best.values[i]) - p.values.begin());
      result.fitted.push_back(sensitivity_band(p, at, result.band));
      result.profiles.push_back(std::move(p));
    }
    best_profiled = nullptr;
    for (std::size_t k = profiled; k < result.profile_evaluations.size(); ++k)
      if (result.profile_evaluations[k].objective < (best_profiled ? best_profiled->objective : best.objective))
        best_profiled = &result.profile_evaluations[k];
    if (!best_profiled) break;
    x.clear();
    for (const double v : best_profiled->values) x.push_back(std::log10(v));
    result.stop_reason += "; restarted from a lower profile point";
  }
  return result;
}

}  // namespace weft::app
