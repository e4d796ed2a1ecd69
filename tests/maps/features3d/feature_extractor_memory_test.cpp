// The extractor owns its buffers: once it has seen a revolution, another of no more points
// allocates nothing (feature_extractor.hpp), so a landmark mapper runs in fixed memory.
#include <random>

#include <gtest/gtest.h>

#include "maps/features3d/feature_extractor.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/range3d/range_frame.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::maps::features3d {
namespace {

// Four walls 6 m away, 8 m long, as one HDL-32E revolution from its centre:
// every pixel's ray to the nearest surface (the floor where it is hit first).
std::vector<Eigen::Vector3f> Room(const range3d::RangeProjection& projection, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0F, 0.01F);
  std::vector<Eigen::Vector3f> points;
  for (int row = 0; row < projection.rows(); ++row) {
    for (int col = 0; col < projection.cols(); ++col) {
      const Eigen::Vector3f d = projection.Unproject(row, col, 1.0F).normalized();
      float range = 1e9F;
      for (int axis = 0; axis < 2; ++axis) {  // walls 8 m long: open corners, four separate planes
        if (std::abs(d[axis]) < 1e-6F) continue;
        const float t = 6.0F / std::abs(d[axis]);
        if (std::abs(d[1 - axis] * t) < 4.0F) range = std::min(range, t);
      }
      if (d.z() < -1e-6F) range = std::min(range, -1.9F / d.z());
      if (range < 50.0F) points.push_back((range + noise(rng)) * d);
    }
  }
  return points;
}

TEST(FeatureExtractorMemory, SecondRevolutionAllocatesNothing) {
  auto options = LoadFeatureOptions(std::filesystem::path(FLAT2D_SOURCE_DIR) / "packaging/config/features3d/features3d.textproto");
  ASSERT_TRUE(options.ok());
  const range3d::RangeProjection projection = range3d::LidarProjection(range3d::SensorModel::kHdl32e, 2160);
  const auto first = Room(projection, 1), second = Room(projection, 2);
  FeatureExtractor extractor(projection, *options);
  const std::size_t planes = extractor.Extract(first, Eigen::Vector3f::UnitZ()).planes.size();
  ASSERT_GE(planes, 4U);  // the walls: the scene is no trivial case
  const std::uint64_t before = testing::AllocationCount();
  const FeatureSet& features = extractor.Extract(second, Eigen::Vector3f::UnitZ());
  const std::uint64_t allocations = testing::AllocationCount() - before;
  EXPECT_EQ(allocations, 0U);
  EXPECT_GE(features.planes.size(), 4U);
}

}  // namespace
}  // namespace flat2d::maps::features3d
