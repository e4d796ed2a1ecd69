// The Gauss-Newton system of NICP (thesis 5.1.3): for each pair the 6D error
// e = T (+) p~_j - p~_i (Eq. 5.10, 5.11), weighed by diag(Omega^s_i, Omega^n_i) (Eq. 5.13)
// and winsorized (Eq. 4.11), linearised with the Jacobian of Eq. 5.17 in (dt, dq).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "localization/registration/correspondence.hpp"
#include "localization/registration/nicp_options.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::localization::registration {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

struct LinearSystem {
  Matrix6d H = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  double chi2 = 0.0;  // winsorized
  int inliers = 0;    // pairs with chi2 below K
};

LinearSystem BuildLinearSystem(const maps::range3d::SurfelCloud& target, const maps::range3d::SurfelCloud& source,
                               const std::vector<Correspondence>& pairs, const Eigen::Isometry3f& target_T_source,
                               const NicpOptions& options);

// T <- dT (+) T (Eq. 5.16): dT from (dt, dq), dq the imaginary part of a unit quaternion.
Eigen::Isometry3d ApplyIncrement(const Vector6d& increment, const Eigen::Isometry3d& target_T_source);

}  // namespace flat2d::localization::registration
