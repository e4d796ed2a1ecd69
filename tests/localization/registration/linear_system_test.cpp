#include "localization/registration/linear_system.hpp"

#include <cstdio>
#include <random>

#include <gtest/gtest.h>

namespace flat2d::localization::registration {
namespace {

using maps::range3d::SurfelCloud;

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// Eq. 5.12-5.17 term by term with full 6x6 matrices: the reference the closed form must match.
LinearSystem Reference(const SurfelCloud& target, const SurfelCloud& source, const std::vector<Correspondence>& pairs,
                       const Eigen::Isometry3d& t, const NicpOptions& options) {
  LinearSystem system;
  for (const Correspondence& pair : pairs) {
    const Eigen::Vector3d x = t * source.points[pair.source].cast<double>();
    const Eigen::Vector3d m = t.linear() * source.normals[pair.source].cast<double>();
    Vector6d e;
    e << x - target.points[pair.target].cast<double>(), m - target.normals[pair.target].cast<double>();
    Matrix6d omega = Matrix6d::Zero();
    omega.topLeftCorner<3, 3>() = target.Information(pair.target).cast<double>();
    if (options.metric == ErrorMetric::kNicp) omega.bottomRightCorner<3, 3>() = options.normal_weight * omega.topLeftCorner<3, 3>();
    Eigen::Matrix<double, 6, 6> j = Matrix6d::Zero();
    j.topLeftCorner<3, 3>().setIdentity();
    j.topRightCorner<3, 3>() = -2.0 * Skew(x);
    j.bottomRightCorner<3, 3>() = -2.0 * Skew(m);
    const double chi2 = e.dot(omega * e);
    const double gamma = chi2 < options.chi2_bound ? 1.0 : options.chi2_bound / chi2;
    // Eq. 6.7: w_i w_j, each point's inverse depth in its own frame; chi2 stays unweighted.
    const double weight = options.inverse_depth_weights ? 1.0 / (source.points[pair.source].cast<double>().norm() *
                                                                 target.points[pair.target].cast<double>().norm())
                                                        : 1.0;
    system.H += weight * gamma * j.transpose() * omega * j;
    system.b += weight * gamma * j.transpose() * omega * e;
    system.chi2 += gamma * chi2;
    system.inliers += chi2 < options.chi2_bound ? 1 : 0;
  }
  return system;
}

SurfelCloud RandomCloud(std::mt19937& rng, std::size_t n) {
  std::uniform_real_distribution<float> unit(-1.0F, 1.0F);
  SurfelCloud cloud;
  cloud.Resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Braces: the draws are made in order (a call's arguments have none).
    cloud.points[i] = 3.0F * Eigen::Vector3f{unit(rng), unit(rng), unit(rng)};
    cloud.normals[i] = Eigen::Vector3f{unit(rng), unit(rng), unit(rng)}.normalized();
    cloud.disc_gain[i] = i % 3 == 0 ? 0.0F : 999.0F;
  }
  return cloud;
}

TEST(LinearSystem, ClosedFormMatchesTheTermByTermSum) {
  std::mt19937 rng(42);
  std::printf("seed 42\n");
  for (const auto& [metric, weighted] : {std::pair{ErrorMetric::kNicp, false}, std::pair{ErrorMetric::kPointToPlane, false},
                                        std::pair{ErrorMetric::kNicp, true}}) {
    const SurfelCloud target = RandomCloud(rng, 400), source = RandomCloud(rng, 400);
    std::vector<Correspondence> pairs;
    for (std::uint32_t i = 0; i < 400; ++i) pairs.push_back({i, (i * 7U) % 400U});
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
    t.translation() = Eigen::Vector3d(0.3, -0.1, 0.05);
    NicpOptions options;
    options.metric = metric;
    options.normal_weight = 2.5;
    options.chi2_bound = 50.0;  // some pairs winsorized, some not
    options.inverse_depth_weights = weighted;
    const LinearSystem expected = Reference(target, source, pairs, t, options);
    const LinearSystem actual = BuildLinearSystem(target, source, pairs, t.cast<float>(), options);
    EXPECT_GT(expected.inliers, 20);
    EXPECT_LT(expected.inliers, 380);
    EXPECT_EQ(actual.inliers, expected.inliers);
    EXPECT_NEAR(actual.chi2, expected.chi2, 1e-4 * expected.chi2);
    EXPECT_LT((actual.H - expected.H).cwiseAbs().maxCoeff(), 1e-4 * expected.H.cwiseAbs().maxCoeff());
    EXPECT_LT((actual.b - expected.b).cwiseAbs().maxCoeff(), 1e-4 * expected.b.cwiseAbs().maxCoeff());
  }
}

TEST(LinearSystem, IncrementIsALeftMultiplication) {
  Vector6d increment;
  increment << 0.1, -0.2, 0.3, 0.0, 0.0, std::sin(0.05);  // 0.1 rad about z: dq = sin(theta / 2) z
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.translation() = Eigen::Vector3d(1, 0, 0);
  const Eigen::Isometry3d result = ApplyIncrement(increment, start);
  EXPECT_NEAR(Eigen::AngleAxisd(result.linear()).angle(), 0.1, 1e-9);
  // dT (+) T: the start's translation is rotated by dR, then dt added.
  EXPECT_NEAR(result.translation().x(), std::cos(0.1) + 0.1, 1e-9);
  EXPECT_NEAR(result.translation().y(), std::sin(0.1) - 0.2, 1e-9);
  EXPECT_NEAR(result.translation().z(), 0.3, 1e-9);
}

}  // namespace
}  // namespace flat2d::localization::registration
