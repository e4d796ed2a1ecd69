// Candidate pairs of NICP and the tests that reject them (thesis 5.1.2, Eq. 5.6-5.8).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "localization/registration/nicp_options.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::localization::registration {

struct Correspondence {
  std::uint32_t target = 0;  // i: the current (fixed) cloud
  std::uint32_t source = 0;  // j: the reference cloud, moved by T
};

// True when target point i and source point j (already moved: p, n in the target frame)
// pass the tests: both normals defined, distance (5.6), curvature log ratio (5.7),
// normal agreement (5.8).
inline bool Compatible(const maps::range3d::SurfelCloud& target, std::size_t i, const Eigen::Vector3f& moved_point,
                       const Eigen::Vector3f& moved_normal, float source_curvature, const NicpOptions& options) {
  if (!target.has_normal(i) || moved_normal.squaredNorm() < 0.5F) return false;
  if ((moved_point - target.points[i]).squaredNorm() > options.max_distance_m * options.max_distance_m) return false;
  constexpr float kMinCurvature = 1e-6F;  // a perfect plane's sigma is 0: log needs a floor
  const float log_ratio = std::log(std::max(target.curvature[i], kMinCurvature)) -
                          std::log(std::max(source_curvature, kMinCurvature));
  if (std::abs(log_ratio) > options.max_log_curvature_ratio) return false;
  return target.normals[i].dot(moved_normal) >= options.min_normal_dot;
}

}  // namespace flat2d::localization::registration
