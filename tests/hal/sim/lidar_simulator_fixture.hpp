// Test fixture of the LiDAR simulator tests: the hand-built scene and drive of
// lidar_test_scene.hpp, a simulator factory, and decoding of simulated packets with the
// project's PacketDecoder into world points placed with the truth pose at each return's
// firing time.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "hal/sim/lidar_simulator.hpp"
#include "hal/velodyne/packet_decoder.hpp"
#include "hal/velodyne/sensor_clock.hpp"
#include "tests/hal/sim/lidar_test_scene.hpp"

namespace flat2d::hal::sim {

using velodyne::Model;
using velodyne::ReturnMode;

inline constexpr Model kModels[] = {Model::kVlp16, Model::kHdl32e, Model::kVlp32c};

struct WorldPoint {
  Eigen::Vector3d world;
  double range_m;
  double world_time_s;
  std::uint8_t intensity;
};

class LidarSimulatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<Scene> scene = Scene::Create(testing::LidarTestScene());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    scene_ = std::make_unique<Scene>(std::move(scene).value());
    Result<Trajectory> trajectory = Trajectory::Create(*scene_, testing::LidarTestDrive());
    ASSERT_TRUE(trajectory.ok()) << trajectory.error().message;
    trajectory_ = std::make_unique<Trajectory>(std::move(trajectory).value());
  }

  // Options for a run that starts moving through the corner of the test drive.
  static LidarOptions Options(Model model) {
    LidarOptions options = DefaultLidarOptions(model);
    options.start_drive_time_s = 3.5;
    return options;
  }

  LidarSimulator Make(const LidarOptions& options, std::uint64_t seed = 1) {
    Result<LidarSimulator> sim = LidarSimulator::Create(*scene_, *trajectory_, options, seed);
    EXPECT_TRUE(sim.ok()) << sim.error().message;
    return std::move(sim).value();
  }

  // Decodes `packets` data packets and places every return in the world with the truth pose
  // at its firing time.
  std::vector<WorldPoint> DecodeToWorld(LidarSimulator& sim, int packets) {
    velodyne::PacketDecoder decoder(sim.laser_table());
    auto decoded = std::make_unique<velodyne::DecodedPacket>();
    std::vector<WorldPoint> points;
    for (int i = 0; i < packets; ++i) {
      const SimulatedPacket& packet = sim.NextDataPacket();
      decoder.Decode(packet.payload, *decoded);
      EXPECT_EQ(decoded->error, velodyne::PacketError::kNone);
      const TimeNs packet_ns = velodyne::ResolveHourRelative(decoded->us_past_hour, packet.device_time_ns);
      for (int f = 0; f < decoded->num_fans; ++f) {
        const velodyne::Fan& fan = decoded->fans[static_cast<std::size_t>(f)];
        for (int l = 0; l < fan.num_lasers; ++l) {
          const velodyne::LaserReturn& r = fan.returns[static_cast<std::size_t>(l)];
          if (r.range_m == 0.0f) continue;
          const double drive_s = sim.DriveTimeS(packet_ns + fan.stamp_ns + r.time_offset_ns);
          const Eigen::Isometry3d world_T_sensor =
              trajectory_->At(drive_s).world_T_vehicle * sim.options().vehicle_T_sensor;
          points.push_back({world_T_sensor * r.xyz.cast<double>(), static_cast<double>(r.range_m),
                            drive_s + trajectory_->world_time_offset_s(), r.intensity});
        }
      }
    }
    return points;
  }

  std::unique_ptr<Scene> scene_;
  std::unique_ptr<Trajectory> trajectory_;
};

}  // namespace flat2d::hal::sim
