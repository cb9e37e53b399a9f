#pragma once
// Mathematical constants and angle conversions, written once for sim, render and app.

namespace weft::base {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr float kPiF = 3.14159265358979323846f;

// Degrees to radians and back.
inline constexpr double deg_to_rad(double degrees) { return degrees * kPi / 180.0; }
inline constexpr double rad_to_deg(double radians) { return radians * 180.0 / kPi; }

}  // namespace weft::base
