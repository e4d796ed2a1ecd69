// Line and plane fitting to one cluster, thesis 8.1.4 (Eq. 8.4-8.6).
//
// The cluster's covariance gives l1 <= l2 <= l3 and u1, u2, u3. A line through the mean
// along u3 is a feature when (l1 + l2) / (l1 + l2 + l3) < eps_l (Eq. 8.5) and the mean
// distance of the points to it is under eps_dl; otherwise a plane through the mean with
// normal u2 x u3 when l1 / (l1 + l2 + l3) < eps_p and the mean distance under eps_dp
// (Eq. 8.6). The line goes first: a plane fits a line's points too, not the other way round.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "maps/features3d/feature_options.pb.h"
#include "maps/features3d/line_plane_features.hpp"

namespace flat2d::maps::features3d {

// The floor of a fit's residual variance: the simulator's and a Velodyne's range noise are
// ~1-2 cm (the HDL-32E manual: < 2 cm).
inline constexpr double kMinResidualSigmaM = 0.01;

using Feature = std::variant<std::monostate, LineFeature, PlaneFeature>;

// The feature the points[indices] make, or monostate when neither model fits. `up` (unit,
// gravity's opposite in the points' frame) measures a plane's height.
Feature FitFeature(const std::vector<Eigen::Vector3f>& points, std::span<const std::int32_t> indices,
                   const FittingOptions& options, const Eigen::Vector3f& up = Eigen::Vector3f::UnitZ());

}  // namespace flat2d::maps::features3d
