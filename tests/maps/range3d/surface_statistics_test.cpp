#include "maps/range3d/surface_statistics.hpp"

#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "maps/range3d/depth_cloud.hpp"
#include "maps/range3d/neighbour_statistics.hpp"
#include "tests/testing/box_scene.hpp"

namespace flat2d::maps::range3d {
namespace {

// A camera 1.5 m up in the office room, looking along +x at the far wall (x = 3 m).
Eigen::Isometry3f CameraLookingAlongX() {
  Eigen::Matrix3f world_R_optical;
  world_R_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // optical z = world x, x = -world y, y = -world z
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = world_R_optical;
  pose.translation() = Eigen::Vector3f(-1.0F, 0.0F, 1.5F);
  return pose;
}

struct Frame {
  SurfelCloud cloud;
  IndexImage image;
};

Frame RenderFrame(float sigma_m) {
  std::mt19937 rng(7);
  const PinholeIntrinsics intrinsics;
  const RangeProjection projection = RangeProjection::Pinhole(intrinsics);
  const auto depth = testing::RenderDepth(testing::OfficeRoom(), intrinsics, CameraLookingAlongX(), sigma_m, rng);
  Frame frame;
  CloudFromDepth(depth, projection, 10.0F, frame.cloud, frame.image);
  SurfaceStatistics(SurfaceStatisticsOptions{}).Compute(projection, frame.image, frame.cloud);
  return frame;
}

TEST(SurfaceStatistics, WallNormalFacesTheCameraAndIsFlat) {
  const Frame frame = RenderFrame(0.0F);
  // The image centre sees the far wall x = 3 m: normal -x in the world = -z optical.
  const auto index = static_cast<std::size_t>(frame.image.at(240, 320));
  ASSERT_TRUE(frame.cloud.has_normal(index));
  EXPECT_NEAR(frame.cloud.points[index].z(), 4.0F, 1e-3F);
  EXPECT_NEAR(frame.cloud.normals[index].z(), -1.0F, 1e-4F);
  EXPECT_LT(frame.cloud.curvature[index], 1e-4F);
  // Disc information (Eq. 5.2 inverted): 1000 along the normal, 1 across.
  const Eigen::Vector3f n = frame.cloud.normals[index];
  EXPECT_NEAR(n.dot(frame.cloud.Information(index) * n), 1000.0F, 1.0F);
  EXPECT_NEAR(Eigen::Vector3f::UnitX().dot(frame.cloud.Information(index) * Eigen::Vector3f::UnitX()), 1.0F, 0.05F);
}

TEST(SurfaceStatistics, NoisyWallsStillGiveTheirNormals) {
  const Frame frame = RenderFrame(0.005F);
  int flat = 0, checked = 0;
  for (int row = 200; row < 280; row += 4) {
    for (int col = 280; col < 360; col += 4) {
      const auto index = static_cast<std::size_t>(frame.image.at(row, col));
      if (!frame.cloud.has_normal(index)) continue;
      ++checked;
      EXPECT_GT(-frame.cloud.normals[index].z(), 0.99F) << row << "," << col;
      flat += frame.cloud.curvature[index] < 0.02F ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 350);
  EXPECT_GT(flat, checked * 9 / 10);
}

TEST(SurfaceStatistics, CornersAreCurvedAndDepthJumpsDoNotBleed) {
  const Frame frame = RenderFrame(0.0F);
  int curved = 0, bled = 0, seen = 0;
  for (std::size_t i = 0; i < frame.cloud.size(); ++i) {
    if (!frame.cloud.has_normal(i)) continue;
    ++seen;
    curved += frame.cloud.curvature[i] > 0.05F ? 1 : 0;
    // Every surface of the room is axis-aligned: a normal that is not means a
    // neighbourhood that mixed two surfaces across a jump or a crease.
    const Eigen::Vector3f n = frame.cloud.normals[i].cwiseAbs();
    bled += n.maxCoeff() < 0.9F ? 1 : 0;
  }
  EXPECT_GT(seen, 250000);
  EXPECT_GT(curved, 0);                 // the creases are there...
  EXPECT_LT(bled, seen / 20);           // ...but only a thin band around them
}

TEST(NeighbourStatistics, AgreesWithTheIntegralImageOnAWall) {
  Frame frame = RenderFrame(0.0F);
  SurfelCloud unorganized;
  unorganized.Resize(0);
  for (int row = 220; row < 260; ++row) {
    for (int col = 300; col < 340; ++col) unorganized.points.push_back(frame.cloud.points[static_cast<std::size_t>(frame.image.at(row, col))]);
  }
  const auto points = unorganized.points;
  unorganized.Resize(points.size());
  unorganized.points = points;
  SurfaceStatisticsOptions options;
  options.radius_m = 0.05F;
  ComputeNeighbourStatistics(options, Eigen::Vector3f::Zero(), unorganized);
  for (std::size_t i = 0; i < unorganized.size(); ++i) {
    ASSERT_TRUE(unorganized.has_normal(i));
    EXPECT_NEAR(unorganized.normals[i].z(), -1.0F, 1e-4F);
  }
}

// AssignSurface's Newton-and-cross-product smallest eigenvector against Eigen's iterative
// double solver, on covariances of planes, lines, blobs and near-degenerate mixes
// (eigenvalue ratios down to 1e-9, where a float solver would lose the smallest).
TEST(SurfaceStatistics, SmallestEigenvectorMatchesTheIterativeSolver) {
  std::mt19937 rng(42);
  std::printf("seed 42\n");
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(-9.0, 0.0);
  const SurfaceStatisticsOptions options;
  SurfelCloud cloud;
  cloud.Resize(1);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Braces: the draws are made in order (a call's arguments have none).
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(Eigen::Vector4d{unit(rng), unit(rng), unit(rng), unit(rng)}.normalized()).toRotationMatrix();
    Eigen::Vector3d lambda{std::pow(10.0, exponent(rng)), std::pow(10.0, exponent(rng)), 1.0};
    if (trial % 4 == 0) lambda.y() = lambda.x() * (1.0 + 1e-3 * std::abs(unit(rng)));  // nearly repeated
    const double scale = 1e-4 * std::pow(10.0, 3.0 * std::abs(unit(rng)));  // (1 cm .. 30 cm)^2
    const Eigen::Matrix3d covariance = scale * rotation * lambda.asDiagonal() * rotation.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> reference(covariance);
    const Eigen::Vector3d values = reference.eigenvalues().cwiseMax(0.0);
    cloud.normals[0].setZero();
    AssignSurface(covariance, Eigen::Vector3f::UnitZ(), options, 0, cloud);
    ASSERT_TRUE(cloud.has_normal(0)) << "trial " << trial;
    const double sigma = values[0] / values.sum();
    EXPECT_NEAR(cloud.curvature[0], sigma, 1e-6 + 1e-5 * sigma) << "trial " << trial;
    // The direction is only defined as far as l0 stands apart from l1.
    if (values[1] - values[0] < 1e-3 * values.sum()) continue;
    ++checked;
    const double alignment = std::abs(cloud.normals[0].cast<double>().dot(reference.eigenvectors().col(0)));
    EXPECT_GT(alignment, std::cos(1e-3)) << "trial " << trial << " lambda " << lambda.transpose();
    EXPECT_GE(cloud.normals[0].z(), 0.0F);  // turned towards the viewpoint
  }
  EXPECT_GT(checked, 500);
}

// Line directions (features3d's thin poles): where the middle eigenvalue is below the
// share of the trace the largest eigenvector comes out, against Eigen's solver; elsewhere
// zero; none at all unless asked for (NICP's clouds stay as they were).
TEST(SurfaceStatistics, LineDirectionOnlyWhereTheNeighbourhoodIsALine) {
  std::mt19937 rng(3);
  std::printf("seed 3\n");
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  SurfaceStatisticsOptions options;
  options.line_max_middle_share = 0.1F;
  SurfelCloud cloud;
  cloud.Resize(1);
  cloud.line_directions.assign(1, Eigen::Vector3f::Zero());
  int lines = 0, others = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Braces: the draws are made in order (a call's arguments have none).
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(Eigen::Vector4d{unit(rng), unit(rng), unit(rng), unit(rng)}.normalized()).toRotationMatrix();
    // Middle eigenvalue from 1e-4 to 0.5 of the largest: lines and planes.
    const double middle = std::pow(10.0, -4.0 + 3.7 * 0.5 * (1.0 + unit(rng)));
    const Eigen::Vector3d lambda(middle * 0.5 * (1.0 + unit(rng)), middle, 1.0);
    const Eigen::Matrix3d covariance = 1e-2 * rotation * lambda.asDiagonal() * rotation.transpose();
    AssignSurface(covariance, Eigen::Vector3f::UnitZ(), options, 0, cloud);
    const double share = lambda.y() / lambda.sum();
    if (std::abs(share - 0.1) < 1e-3) continue;  // at the cut either answer is right
    if (share < 0.1) {
      ++lines;
      ASSERT_TRUE(cloud.has_line_direction(0)) << "trial " << trial;
      const double alignment = std::abs(cloud.line_directions[0].cast<double>().dot(rotation.col(2)));
      EXPECT_GT(alignment, std::cos(1e-3)) << "trial " << trial << " lambda " << lambda.transpose();  // float
    } else {
      ++others;
      EXPECT_FALSE(cloud.has_line_direction(0)) << "trial " << trial << " lambda " << lambda.transpose();
    }
  }
  EXPECT_GT(lines, 300);
  EXPECT_GT(others, 300);

  const Frame frame = RenderFrame(0.0F);  // default options: none computed
  EXPECT_TRUE(frame.cloud.line_directions.empty());
}

}  // namespace
}  // namespace flat2d::maps::range3d
