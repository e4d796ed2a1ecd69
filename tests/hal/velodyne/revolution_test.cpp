#include "hal/velodyne/revolution.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"

namespace flat2d::hal::velodyne {
namespace {

Fan MakeFan(double azimuth_deg, TimeNs stamp, bool with_return = true) {
  Fan fan;
  fan.azimuth_rad = static_cast<float>(azimuth_deg * kDegToRad);
  fan.stamp_ns = stamp;
  fan.num_lasers = 16;
  if (with_return) {
    fan.returns[3].range_m = 5.0f;
    fan.num_points = 1;
  }
  return fan;
}

// Fans every `step_deg` from `start_deg` for `turns` turns; returns completed revolutions.
std::vector<Revolution> Spin(RevolutionAssembler& assembler, double start_deg, double step_deg,
                            double turns) {
  std::vector<Revolution> done;
  const int count = static_cast<int>(turns * 360.0 / step_deg);
  for (int i = 0; i < count; ++i) {
    const Fan fan = MakeFan(std::fmod(start_deg + i * step_deg, 360.0), i * 1000);
    if (const Revolution* r = assembler.Add(std::span(&fan, 1))) done.push_back(*r);
  }
  if (const Revolution* r = assembler.Flush()) done.push_back(*r);
  return done;
}

TEST(RevolutionAssembler, CutsAtTheWrapAndMarksPartialEnds) {
  RevolutionAssembler assembler({}, Model::kVlp16, ReturnMode::kStrongest);
  const auto revolutions = Spin(assembler, 200.0, 0.2, 3.0);
  ASSERT_EQ(revolutions.size(), 4u);  // 160 deg partial, 2 full turns, 200 deg partial
  EXPECT_FALSE(revolutions[0].complete);
  EXPECT_TRUE(revolutions[1].complete);
  EXPECT_TRUE(revolutions[2].complete);
  EXPECT_FALSE(revolutions[3].complete);
  EXPECT_EQ(revolutions[1].fans.size(), 1800u);
  EXPECT_EQ(revolutions[1].points, 1800);
  EXPECT_NEAR(revolutions[1].fans.front().azimuth_rad, 0.0, 1e-4);
  EXPECT_NEAR(revolutions[1].swept_azimuth_rad, (360.0 - 0.2) * kDegToRad, 1e-3);
  EXPECT_EQ(revolutions[2].sequence, 2u);
  EXPECT_LT(revolutions[1].start_ns(), revolutions[1].end_ns());
}

TEST(RevolutionAssembler, CutAngleIsConfigurable) {
  RevolutionOptions options;
  options.cut_azimuth_rad = 90.0 * kDegToRad;
  RevolutionAssembler assembler(options, Model::kVlp16, ReturnMode::kStrongest);
  const auto revolutions = Spin(assembler, 0.0, 0.5, 2.0);
  ASSERT_GE(revolutions.size(), 2u);
  EXPECT_NEAR(revolutions[1].fans.front().azimuth_rad, 90.0 * kDegToRad, 1e-4);
}

TEST(RevolutionAssembler, JitterAndDualPairsDoNotCut) {
  RevolutionAssembler assembler({}, Model::kVlp16, ReturnMode::kDual);
  std::vector<Fan> fans;
  for (int i = 0; i < 100; ++i) {
    const double azimuth = 10.0 + i * 0.4 - (i % 3 == 0 ? 0.05 : 0.0);  // backwards wobble
    fans.push_back(MakeFan(azimuth, i));
    fans.push_back(MakeFan(azimuth, i));  // dual pair: same azimuth
  }
  EXPECT_EQ(assembler.Add(fans), nullptr);
}

TEST(RevolutionAssembler, AzimuthJumpCutsOnlyWhenItCrossesTheCut) {
  RevolutionAssembler assembler({}, Model::kVlp32c, ReturnMode::kStrongest);
  // A FOV-limited sensor: 270 -> 360 -> 90, then a jump back to 270.
  std::vector<Revolution> done;
  TimeNs t = 0;
  for (int turn = 0; turn < 3; ++turn) {
    for (double azimuth = 270.0; azimuth < 450.0; azimuth += 0.2) {
      const Fan fan = MakeFan(std::fmod(azimuth, 360.0), t++);
      if (const Revolution* r = assembler.Add(std::span(&fan, 1))) done.push_back(*r);
    }
  }
  ASSERT_EQ(done.size(), 3u);  // one cut at 0 deg per turn; the 90 -> 270 jump is not one
  EXPECT_TRUE(done[1].complete);
  EXPECT_NEAR(done[1].swept_azimuth_rad, 180.0 * kDegToRad, 0.01);  // jump not counted as sweep
}

TEST(RevolutionAssembler, OverflowDropsAndCountsFans) {
  RevolutionOptions options;
  options.max_fans = 100;
  RevolutionAssembler assembler(options, Model::kVlp16, ReturnMode::kStrongest);
  const auto revolutions = Spin(assembler, 0.0, 1.0, 1.5);
  ASSERT_FALSE(revolutions.empty());
  EXPECT_EQ(revolutions[0].fans.size(), 100u);
  EXPECT_EQ(revolutions[0].dropped_fans, 260);
  EXPECT_EQ(revolutions[0].fans.capacity(), 100u);
}

TEST(RevolutionAssembler, BufferIsSizedForTheSlowestRotation) {
  // VLP-16 single return: 754 packets/s x 24 fans = 18,087 fans/s; at 5 Hz with 10 %
  // margin 3,979 fans.
  EXPECT_EQ(MaxFansPerRevolution(Model::kVlp16, ReturnMode::kStrongest, 5.0), 3979u);
  EXPECT_EQ(MaxFansPerRevolution(Model::kHdl32e, ReturnMode::kDual, 5.0), 9549u);  // 3,617 packets/s
}

}  // namespace
}  // namespace flat2d::hal::velodyne
