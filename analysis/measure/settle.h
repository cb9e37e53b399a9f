#pragma once
// Settle time: when a motion has "basically stopped" (seed 002, Zhou & Sze,
// section 4.6: the two-corner hangs stop moving by about 2 s and 2.4 s).
//
// The criterion weft uses is the cloth's largest vertex speed staying below
// settle_speed_threshold_m_s = 1 cm/s. An absolute speed, because "stopped moving" is what a
// viewer judges: at 1 cm/s a point moves less than 0.5 mm between frames at 24 fps, under a
// pixel of a typical render, and so does the whole sheet. A threshold relative to the peak
// kinetic energy would instead call a sheet that falls faster settled later, and the kinetic
// energy, a sum over the sheet, hides one corner still swinging. The function itself takes any
// series and threshold (kinetic energy against 1e-3 of its peak works the same way).

#include <optional>
#include <vector>

namespace weft::analysis {

inline constexpr double settle_speed_threshold_m_s = 0.01;

// The first time after which value(t) stays below `threshold` until the end of the series:
// with i the last sample at or above the threshold, the time between samples i and i + 1 where
// the series crosses the threshold — interpolated linearly in log(value) when both samples are
// > 0 (exact for an exponential decay, the usual tail of a damped motion), linearly in value
// otherwise. time_s[0] when every sample is below; none when the last sample is not below
// (not settled within the series).
// time_s: strictly increasing sample times, s; value: same length, e.g. max speed in m/s.
// Throws std::invalid_argument for an empty series, sizes that differ, times not strictly
// increasing, a non-finite value, or a threshold that is not finite and > 0.
std::optional<double> settle_time_s(const std::vector<double>& time_s,
                                    const std::vector<double>& value, double threshold);

}  // namespace weft::analysis
