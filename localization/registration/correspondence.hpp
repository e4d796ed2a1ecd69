// Candidate pairs of NICP and the tests that reject them (thesis 5.1.2, Eq. 5.6-5.8).
#pragma once

#include <algorithm>
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

// The thresholds of the tests, prepared once per search.
struct CompatibilityTest {
  explicit CompatibilityTest(const NicpOptions& options)
      : surface_tests(options.metric == ErrorMetric::kNicp),
        max_distance_squared(options.max_distance_m * options.max_distance_m),
        max_curvature_ratio(std::exp(options.max_log_curvature_ratio)),
        curvature_floor(std::max(options.curvature_floor, 1e-6F)),
        min_normal_dot(options.min_normal_dot) {}
  // The point-to-plane baseline selects "based only on point distance" (5.3): no
  // curvature or normal test.
  bool surface_tests;
  float max_distance_squared;
  float max_curvature_ratio;  // |log a - log b| > eps_sigma  <=>  max(a, b) > e^eps_sigma min(a, b)
  float curvature_floor;      // NicpOptions::curvature_floor, at least 1e-6 (a perfect plane has 0)
  float min_normal_dot;
};

// True when target point i and source point j (already moved: p, n in the target frame)
// pass the tests: both normals defined, distance (5.6), and for NICP the curvature log
// ratio (5.7) and normal agreement (5.8).
inline bool Compatible(const maps::range3d::SurfelCloud& target, std::size_t i, const Eigen::Vector3f& moved_point,
                       const Eigen::Vector3f& moved_normal, float source_curvature, const CompatibilityTest& test) {
  if (!target.has_normal(i) || moved_normal.squaredNorm() < 0.5F) return false;
  if ((moved_point - target.points[i]).squaredNorm() > test.max_distance_squared) return false;
  if (!test.surface_tests) return true;
  const float a = std::max(target.curvature[i], test.curvature_floor);
  const float b = std::max(source_curvature, test.curvature_floor);
  if (std::max(a, b) > test.max_curvature_ratio * std::min(a, b)) return false;
  return target.normals[i].dot(moved_normal) >= test.min_normal_dot;
}

}  // namespace flat2d::localization::registration
