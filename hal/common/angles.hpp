// Degree <-> radian factors. Angles are radians everywhere inside flat2d; degrees appear
// only at the edges (Velodyne packets and calibration files, DBC signals, reports).
#pragma once

#include <numbers>

namespace flat2d {

inline constexpr double kDegToRad = std::numbers::pi / 180.0;
inline constexpr double kRadToDeg = 180.0 / std::numbers::pi;

}  // namespace flat2d
