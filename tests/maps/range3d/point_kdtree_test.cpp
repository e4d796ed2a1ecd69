// PointKdTree: the nearest member on (p, alpha n) against a brute-force search, points
// without a normal left out.
#include "maps/range3d/point_kdtree.hpp"

#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace flat2d::maps::range3d {
namespace {

struct RandomSurfels {
  std::vector<Eigen::Vector3f> points, normals;
};

RandomSurfels MakeRandomSurfels(std::size_t count, std::mt19937& rng) {
  std::uniform_real_distribution<float> coordinate(-5.0F, 5.0F);
  RandomSurfels surfels;
  for (std::size_t i = 0; i < count; ++i) {
    surfels.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
    // Every 10th normal undefined (zero): the 6D tree leaves those points out.
    surfels.normals.push_back(i % 10 == 3 ? Eigen::Vector3f::Zero()
                                          : Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized());
  }
  return surfels;
}

// The brute-force nearest on (p, alpha n) among points with a normal: index, squared distance.
std::pair<std::int64_t, float> BruteNearest(const RandomSurfels& surfels, float alpha, const float* query) {
  std::int64_t best = -1;
  float best_squared = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < surfels.points.size(); ++i) {
    if (surfels.normals[i].squaredNorm() < 0.5F) continue;
    float squared = 0.0F;
    for (int k = 0; k < 3; ++k) {
      const float dp = surfels.points[i][k] - query[k];
      const float dn = alpha * surfels.normals[i][k] - query[3 + k];
      squared += dp * dp + dn * dn;
    }
    if (squared < best_squared) best = static_cast<std::int64_t>(i), best_squared = squared;
  }
  return {best, best_squared};
}

TEST(PointKdTree, NearestOnPointsAndNormalsMatchesABruteForceSearch) {
  std::mt19937 rng(5);
  const RandomSurfels surfels = MakeRandomSurfels(2000, rng);
  constexpr float kAlpha = 1.0F / 3.0F;
  const PointKdTree<6> tree(surfels.points, &surfels.normals, kAlpha);
  std::uniform_real_distribution<float> coordinate(-6.0F, 6.0F);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3f n = Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
    const float query[6] = {coordinate(rng), coordinate(rng), coordinate(rng), kAlpha * n.x(), kAlpha * n.y(), kAlpha * n.z()};
    const auto [index, squared] = tree.Nearest(query);
    const auto [brute_index, brute_squared] = BruteNearest(surfels, kAlpha, query);
    EXPECT_EQ(index, brute_index) << "trial " << trial;
    EXPECT_NEAR(squared, brute_squared, 1e-4F) << "trial " << trial;
  }
}

TEST(PointKdTree, AnEmptyTreeFindsNothing) {
  const std::vector<Eigen::Vector3f> points{{1.0F, 2.0F, 3.0F}};
  const std::vector<Eigen::Vector3f> normals{Eigen::Vector3f::Zero()};  // no member
  const PointKdTree<6> tree(points, &normals, 1.0F);
  const float query[6] = {1.0F, 2.0F, 3.0F, 0.0F, 0.0F, 0.0F};
  EXPECT_EQ(tree.Nearest(query).first, -1);
}

}  // namespace
}  // namespace flat2d::maps::range3d
