// The factor math of SE(2) pose graphs, shared by the batch optimizer (graph_optimizer.hpp)
// and the daemon's sliding window: errors and Jacobians of between, prior (unary) and
// max-mixture factors (thesis 3.4, Alg. 6; thesis 7.2.1; Olson & Agarwal, "Inference on
// networks of mixtures for robust robot mapping", RSS 2012).
//
// Perturbation (the manifold's retraction, thesis 3.4.2's "boxplus"): an increment
// delta = (dx, dy, dtheta) is ADDED TO THE COMPONENTS of a pose, theta wrapped:
//   x [+] delta = (x + dx, y + dy, wrap(theta + dtheta))        (F1)
// the same convention as the Se2 covariance (localization/odometry/se2.hpp), so the
// inverse of the information matrix at the solution is directly a component covariance.
//
// Between factor, measurement z = i_T_j (g2o's EDGE_SE2 convention):
//   e_t = Rz^T (Ri^T (tj - ti) - tz)                                 (F2)
//   e_theta = wrap(thj - thi - thz)                  (AngleResidual::kWrapped, g2o)
//           = 2 sin(wrap(thj - thi - thz) / 2)        (AngleResidual::kChord, SE-Sync)
// With S = [0 -1; 1 0] and d = tj - ti the Jacobians with respect to F1 are
//   de_t/dti = -Rz^T Ri^T,  de_t/dthi = -Rz^T Ri^T S d,  de_t/dtj = Rz^T Ri^T,
//   de_theta/dthi = -c, de_theta/dthj = c,  c = 1 (wrapped) or cos(angle / 2) (chord).  (F3)
// The chord residual makes e^T diag(tau, tau, 2 kappa) e equal SE-Sync's edge cost
// tau |tj - ti - Ri tz|^2 + kappa |Rj - Ri Rz|_F^2 (= 4 kappa (1 - cos)), see graph_costs.hpp.
//
// Prior factor against a fixed pose z: e = (x - zx, y - zy, wrap(th - zth)), J = I.     (F4)
//
// Max-mixture: a factor's likelihood is max_k w_k |L_k|^(1/2) exp(-e^T L_k e / 2) over a few
// Gaussian components sharing the error e (the match and a broad null hypothesis). The max
// replaces the sum so the negative log stays a least-squares term: the component with the
// largest likelihood at the current estimate is chosen, and the factor contributes
//   e^T L_k e + offset_k,  offset_k = 2 (max_m log(w_m |L_m|^(1/2)) - log(w_k |L_k|^(1/2)))  (F5)
// (offset_k >= 0, so the cost stays non-negative and continuous where components switch).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>

#include "localization/odometry/se2.hpp"

namespace flat2d::localization::graph {

enum class AngleResidual {
  kWrapped,  // g2o / GTSAM: the wrapped angle difference
  kChord,    // SE-Sync: 2 sin(angle / 2), the chordal distance of the rotations / sqrt(2)
};

// F1: the pose with `delta` added to its components.
Se2 Retract(const Se2& pose, const Eigen::Vector3d& delta);

// An error and its Jacobians with respect to F1 perturbations of the two poses.
struct BetweenLinearization {
  Eigen::Vector3d error;
  Eigen::Matrix3d jacobian_i;
  Eigen::Matrix3d jacobian_j;
};

// F2.
Eigen::Vector3d BetweenError(const Se2& pose_i, const Se2& pose_j, const Se2& measurement,
                             AngleResidual angle = AngleResidual::kWrapped);

// F2 and F3.
BetweenLinearization LinearizeBetween(const Se2& pose_i, const Se2& pose_j,
                                      const Se2& measurement,
                                      AngleResidual angle = AngleResidual::kWrapped);

// F4; its Jacobian is the identity.
Eigen::Vector3d PriorError(const Se2& pose, const Se2& measurement);

// One Gaussian of a max-mixture: weight w_k and information L_k (F5).
struct MixtureComponent {
  double weight = 1.0;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

// At most this many components per factor, so a factor is a fixed-size value (the sliding
// window preallocates them); a match against a null hypothesis needs two.
inline constexpr std::size_t kMaxMixtureComponents = 4;

struct MaxMixture {
  std::array<MixtureComponent, kMaxMixtureComponents> components{};
  std::size_t size = 0;
};

// The usual robust loop closure: the match Gaussian (weight 1 - null_weight) against a null
// hypothesis with the same mean and information `match_information * null_information_scale`
// (e.g. 1e-6: a standard deviation 1000 times wider) and weight null_weight.
MaxMixture MakeNullHypothesisMixture(const Eigen::Matrix3d& match_information, double null_weight,
                                     double null_information_scale);

// The winning component at an error and what it contributes (F5).
struct MixtureChoice {
  std::size_t component = 0;
  Eigen::Matrix3d information;
  double offset = 0.0;  // F5's offset_k
  double cost = 0.0;    // e^T L_k e + offset_k
};

// Requires mixture.size >= 1 and positive weights and determinants.
MixtureChoice SelectMixtureComponent(const MaxMixture& mixture, const Eigen::Vector3d& error);

}  // namespace flat2d::localization::graph
