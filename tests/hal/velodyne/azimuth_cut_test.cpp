#include "hal/velodyne/azimuth_cut.hpp"

#include <numbers>

#include <gtest/gtest.h>

namespace flat2d::hal::velodyne {
namespace {

constexpr float kDegToRadF = static_cast<float>(std::numbers::pi / 180.0);

TEST(AzimuthCut, WrapsOncePerTurnAtTheCut) {
  AzimuthCut cut(90.0 * std::numbers::pi / 180.0);
  int wraps = 0;
  double swept = 0.0;
  for (int i = 0; i < 3 * 1800; ++i) {  // three turns in 0.2 deg steps from azimuth 0
    const AzimuthStep step = cut.Next(static_cast<float>(i % 1800) * 0.2f * kDegToRadF);
    wraps += step.wraps;
    if (step.wraps) {
      EXPECT_EQ(i % 1800, 450) << i;  // the first fan at or past 90 deg
    }
    swept += step.forward_step_rad;
  }
  EXPECT_EQ(wraps, 3);
  EXPECT_NEAR(swept, 3 * 2 * std::numbers::pi - 0.8 * std::numbers::pi / 180.0, 1e-3);  // wrap steps add nothing
}

TEST(AzimuthCut, JitterAndDualReturnStepsBackDoNotWrap) {
  AzimuthCut cut;
  EXPECT_FALSE(cut.Next(10.0f * kDegToRadF).wraps);
  EXPECT_FALSE(cut.Next(9.9f * kDegToRadF).wraps);   // a dual-return pair steps back a little
  EXPECT_FALSE(cut.Next(100.0f * kDegToRadF).wraps);  // a forward jump (FOV-limited sensor)
  EXPECT_FALSE(cut.Next(20.0f * kDegToRadF).wraps);   // 80 deg back: jitter bound is 90
  EXPECT_FALSE(cut.Next(359.0f * kDegToRadF).wraps);
  EXPECT_TRUE(cut.Next(1.0f * kDegToRadF).wraps);     // 358 deg back relative to the cut at 0
  cut.Reset();
  EXPECT_FALSE(cut.Next(0.5f * kDegToRadF).wraps);    // no previous azimuth after Reset
}

}  // namespace
}  // namespace flat2d::hal::velodyne
