#include "analysis/measure/settle.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::analysis {

std::optional<double> settle_time_s(const std::vector<double>& time_s,
                                    const std::vector<double>& value, double threshold) {
  if (time_s.empty() || time_s.size() != value.size())
    throw std::invalid_argument("settle_time_s: expected equally long, non-empty series, got " +
                                std::to_string(time_s.size()) + " times and " +
                                std::to_string(value.size()) + " values");
  if (!(std::isfinite(threshold) && threshold > 0.0))
    throw std::invalid_argument("settle_time_s: the threshold must be finite and > 0");
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!std::isfinite(value[i]) || !std::isfinite(time_s[i]))
      throw std::invalid_argument("settle_time_s: sample " + std::to_string(i) + " is not finite");
    if (i > 0 && !(time_s[i] > time_s[i - 1]))
      throw std::invalid_argument("settle_time_s: times must increase strictly (sample " +
                                  std::to_string(i) + ")");
  }
  std::size_t last_above = value.size();
  for (std::size_t i = value.size(); i-- > 0;) {
    if (value[i] >= threshold) {
      last_above = i;
      break;
    }
  }
  if (last_above == value.size()) return time_s.front();
  if (last_above + 1 == value.size()) return std::nullopt;
  const double t0 = time_s[last_above], t1 = time_s[last_above + 1];
  const double v0 = value[last_above], v1 = value[last_above + 1];  // v0 ≥ threshold > v1
  const double fraction = v1 > 0.0 ? std::log(v0 / threshold) / std::log(v0 / v1)
                                   : (v0 - threshold) / (v0 - v1);
  return t0 + fraction * (t1 - t0);
}

}  // namespace weft::analysis
