#include "hal/velodyne/laser_table.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"

namespace flat2d::hal::velodyne {
namespace {

TEST(LaserTable, Vlp16ElevationsInterleaveFromMinus15To15) {
  const LaserTable table = DefaultLaserTable(Model::kVlp16);
  ASSERT_EQ(table.num_lasers, 16);
  EXPECT_DOUBLE_EQ(table.distance_resolution_m, 0.002);
  for (int id = 0; id < 16; ++id) {
    const double expected = id % 2 == 0 ? -15.0 + id : 1.0 + (id - 1);
    EXPECT_NEAR(table.lasers[static_cast<std::size_t>(id)].elevation_rad * kRadToDeg, expected,
                1e-12)
        << "laser " << id;
  }
}

TEST(LaserTable, Hdl32eElevationsSpan4Over3DegreeSteps) {
  const LaserTable table = DefaultLaserTable(Model::kHdl32e);
  ASSERT_EQ(table.num_lasers, 32);
  EXPECT_NEAR(table.lasers[0].elevation_rad * kRadToDeg, -30.67, 1e-12);
  EXPECT_NEAR(table.lasers[31].elevation_rad * kRadToDeg, 10.67, 1e-12);
  // Sorted by elevation, consecutive lasers are 4/3 deg apart (manual rounds to 0.01).
  std::vector<double> sorted;
  for (int id = 0; id < 32; ++id) sorted.push_back(ManualElevationDeg(Model::kHdl32e, id));
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    EXPECT_NEAR(sorted[i] - sorted[i - 1], 4.0 / 3.0, 0.011) << "between " << i - 1 << " and " << i;
  }
}

TEST(LaserTable, Vlp32cHasAzimuthOffsetsAnd4mmResolution) {
  const LaserTable table = DefaultLaserTable(Model::kVlp32c);
  EXPECT_DOUBLE_EQ(table.distance_resolution_m, 0.004);
  EXPECT_NEAR(table.lasers[0].elevation_rad * kRadToDeg, -25.0, 1e-12);
  EXPECT_NEAR(table.lasers[29].elevation_rad * kRadToDeg, 15.0, 1e-12);
  // Manual offset +1.4 deg for laser 0 is rot_correction -1.4 deg in driver convention.
  EXPECT_NEAR(table.lasers[0].rot_correction_rad * kRadToDeg, -1.4, 1e-12);
  EXPECT_NEAR(table.lasers[1].rot_correction_rad * kRadToDeg, 4.2, 1e-12);
}

}  // namespace
}  // namespace flat2d::hal::velodyne
