// The amplitude spectrum of a drape outline and the distance between two (see outline_spectrum.h).

#include "app/fit/outline_spectrum.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"

namespace weft::app {

std::vector<double> outline_amplitudes(const std::vector<double>& radii, int harmonics) {
  const std::size_t n = radii.size();
  if (harmonics < 2 || n < 2 * static_cast<std::size_t>(harmonics) + 1)
    throw std::invalid_argument("outline_amplitudes: " + std::to_string(harmonics) +
                                " harmonics need at least 2K + 1 bins and K ≥ 2, got " +
                                std::to_string(n) + " bins");
  std::vector<double> a(static_cast<std::size_t>(harmonics) + 1, 0.0);
  for (std::size_t k = 0; k < a.size(); ++k) {
    double re = 0.0, im = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double theta = 2.0 * base::kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(n);
      re += radii[j] * std::cos(static_cast<double>(k) * theta);
      im += radii[j] * std::sin(static_cast<double>(k) * theta);
    }
    // r = a₀ + Σ aₖ cos(kθ + φₖ): a₀ = mean, aₖ = 2 |Σ r e^{−ikθ}| / N.
    a[k] = (k == 0 ? 1.0 : 2.0) * std::hypot(re, im) / static_cast<double>(n);
  }
  return a;
}

double outline_spectrum_distance(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.size() < 3)
    throw std::invalid_argument("outline_spectrum_distance: amplitude lists of " +
                                std::to_string(a.size()) + " and " + std::to_string(b.size()) +
                                " harmonics (expected the same number, at least 3)");
  double sum = (a[0] - b[0]) * (a[0] - b[0]);
  for (std::size_t k = 2; k < a.size(); ++k) sum += 0.5 * (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(sum);
}

}  // namespace weft::app
