// Slope-based, multi-class structure detection along one vertical fan (thesis 7.1.3).
//
// A fan's returns, ordered bottom-up, lie roughly in one vertical plane; with the dummy
// return at the vehicle's origin on the ground prepended, consecutive returns trace the
// terrain's profile outwards. Steps: (1) place every return in that plane at (horizontal
// range from the vehicle, z); (2) for each window of `fit_points` consecutive returns
// (2 = the thesis' consecutive pair; 3+ fits a total-least-squares line, smoother against
// range noise) take the slope of the profile, 0 = level, pi/2 = vertical; (3) class the
// window hazard above hazard_slope, slammable above slammable_slope, free otherwise; (4) mark
// an obstacle window, conservatively, on its return nearest the vehicle, and a free window on
// all its returns, keeping the strongest class a return gets from any window. The dummy
// return is never marked: it is where the vehicle stands.
//
// Beyond the thesis, see-through structure (fences, railings, a bar over the ground): the
// beams between two returns of such a structure pass through it and hit the ground behind,
// so no consecutive pair is steep. (5) Any two returns below `see_through_max_height_m`
// whose profile between them is farther away than both (nothing was hit in front of the
// gap) are a pair too; steeper than slammable_slope, their nearer return is slammable.
#pragma once

#include <span>

#include <Eigen/Core>

#include "hal/common/angles.hpp"
#include "maps/grid/cell_class.hpp"

namespace flat2d::maps {

struct SlopeThresholds {
  double hazard_slope_rad = 15.0 * kDegToRad;
  double slammable_slope_rad = 80.0 * kDegToRad;
  int fit_points = 2;  // returns per slope estimate, >= 2 (the dummy return counts)
  // Step (5) for returns at most this high above the ground; 0 disables it. Bounded so that
  // a canopy above the ground it overhangs (tree crowns start at 2-3 m) is no wall.
  double see_through_max_height_m = 0.0;
};

// Classes `classes[i]` for `returns[i]`, the valid returns of one fan ordered bottom-up in the
// ground-level vehicle frame (z = 0 on the ground below the vehicle origin). classes must be
// as long as returns. Allocates nothing.
void ClassifyFan(std::span<const Eigen::Vector3f> returns, const SlopeThresholds& thresholds,
                 std::span<CellClass> classes);

// The slope (rad, [0, pi/2]) of the total-least-squares line through profile points
// (horizontal range, z): the principal direction of their scatter.
double ProfileSlope(std::span<const Eigen::Vector2d> profile);

}  // namespace flat2d::maps
