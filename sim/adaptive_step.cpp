#include "sim/adaptive_step.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace weft::sim {
namespace {

constexpr double kSafety = 0.9;  // a rejected step is redone a little below the strain limit
constexpr double kGrow = 1.25, kShrink = 0.7, kShrinkUnconverged = 0.5;

}  // namespace

AdaptiveStep::AdaptiveStep(const AdaptiveStepSettings& settings)
    : m_settings(settings), m_next_s(settings.max_step_s) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("simulation.adaptive_step: " + what);
  };
  if (!(settings.min_step_s > 0.0)) fail("min_step must be positive");
  if (!(settings.max_step_s >= settings.min_step_s) || !std::isfinite(settings.max_step_s)) {
    std::ostringstream what;
    what << "max_step (" << settings.max_step_s << " s) must be finite and at least min_step ("
         << settings.min_step_s << " s)";
    fail(what.str());
  }
  if (!(settings.max_prediction_strain > 0.0) || !std::isfinite(settings.max_prediction_strain))
    fail("max_prediction_strain must be a positive number");
}

double AdaptiveStep::next_step(double remaining_s) const {
  if (!(remaining_s > 0.0)) return 0.0;
  const double steps = std::ceil(remaining_s / m_next_s - 1e-9);
  return remaining_s / std::max(1.0, steps);
}

bool AdaptiveStep::reject(double h_s, double strain) {
  const double limit = m_settings.max_prediction_strain;
  if (!(strain > limit) || h_s <= m_settings.min_step_s) return false;
  // Strain grows as h²: the step that would have met the limit is h √(ε_max/ε).
  m_next_s = std::clamp(h_s * std::sqrt(kSafety * limit / strain), m_settings.min_step_s,
                        m_settings.max_step_s);
  return true;
}

void AdaptiveStep::accept(double h_s, int iterations, bool converged) {
  const double factor = !converged ? kShrinkUnconverged
                        : iterations <= 1 ? kGrow
                        : iterations == 2 ? 1.0
                                          : kShrink;
  m_next_s = std::clamp(h_s * factor, m_settings.min_step_s, m_settings.max_step_s);
}

}  // namespace weft::sim
