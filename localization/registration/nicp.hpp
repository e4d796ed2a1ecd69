// NICP: normal-based ICP (thesis 5.1; Serafin and Grisetti, IROS 2015). Aligns a source
// cloud to a target by least squares on points and normals:
//
//   1. correspondences at the current estimate (projective or KD-tree finder, 5.1.2);
//   2. the winsorized 6D system H, b (Eq. 5.12-5.17, 4.11);
//   3. a damped Gauss-Newton step (H + lambda I) dT = -b (Eq. 5.15), T <- dT (+) T (5.16);
//   4. repeat a fixed number of times (10, 5.3) or until the step vanishes.
//
// With ErrorMetric::kPointToPlane (Omega^n = 0) the same loop is the point-to-plane
// baseline the thesis compares against. Both clouds carry their statistics already
// (maps/range3d/surface_statistics.hpp); the target's are what weigh the errors.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "localization/registration/correspondence_finder.hpp"
#include "localization/registration/nicp_options.hpp"
#include "localization/registration/registration_result.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::localization::registration {

class Nicp {
 public:
  explicit Nicp(const NicpOptions& options) : options_(options) {}

  // `finder` is bound to `target`. `guess` is target_T_source to start from.
  RegistrationResult Register(const maps::range3d::SurfelCloud& target, CorrespondenceFinder& finder,
                              const maps::range3d::SurfelCloud& source, const Eigen::Isometry3d& guess);

  const NicpOptions& options() const { return options_; }

 private:
  const NicpOptions options_;
  std::vector<Correspondence> pairs_;  // reused: sized by the largest cloud seen
};

}  // namespace flat2d::localization::registration
