// The LiDAR simulator against the project's own Velodyne decoder and the scene's geometry:
// every packet decodes (model identified, no loss), decoded points transformed with the
// truth pose at their firing time lie on the scene's surfaces, dropouts, range limits,
// rotation rates, determinism, position packets and GNSS fixes.
#include "hal/sim/lidar_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hal/net/udp_datagram.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "tests/hal/sim/lidar_simulator_fixture.hpp"
#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::sim {
namespace {

TEST_F(LidarSimulatorTest, EveryPacketDecodesAndTheModelIsIdentified) {
  for (const Model model : kModels) {
    SCOPED_TRACE(std::string(velodyne::ModelName(model)));
    LidarSimulator sim = Make(Options(model));
    velodyne::VelodyneStream stream({});  // model from the packets
    const double seconds = 0.5;
    const TimeNs end_ns = sim.UnixTimeNs(sim.options().start_drive_time_s + seconds);
    TimeNs previous_device_ns = 0;
    std::int64_t max_step_error_ns = 0;
    const double period_ns = 1e3 * velodyne::PacketPeriodUs(model, ReturnMode::kStrongest);
    while (sim.next_capture_time_ns() < end_ns) {
      const SimulatedPacket& packet = sim.Next();
      net::UdpDatagram datagram;
      datagram.receive_time_ns = packet.capture_time_ns;
      datagram.destination.port = packet.destination_port;
      datagram.payload = packet.payload;
      stream.Push(datagram);
      if (packet.kind != LidarPacketKind::kData) continue;
      const std::uint32_t us = velodyne::ReadU32(packet.payload.data() + velodyne::kTimestampOffset);
      const TimeNs device_ns = velodyne::ResolveHourRelative(us, packet.capture_time_ns);
      if (previous_device_ns != 0) {
        const auto error = std::llabs(device_ns - previous_device_ns - std::llround(period_ns));
        max_step_error_ns = std::max<std::int64_t>(max_step_error_ns, error);
      }
      previous_device_ns = device_ns;
    }
    stream.Finish();
    const velodyne::VelodyneStreamStats& stats = stream.stats();
    ASSERT_TRUE(stream.identification().has_value());
    EXPECT_EQ(stream.identification()->model, model);
    EXPECT_EQ(stats.malformed, 0u);
    EXPECT_EQ(stats.bad_position_packets, 0u);
    EXPECT_EQ(stats.lost_packets, 0u);
    EXPECT_EQ(stats.out_of_order, 0u);
    EXPECT_EQ(stats.pauses, 0u);
    // The model's packet rate (manuals 9.x) and the option's position-packet rate; a data
    // packet is captured one packet period after its first firing, hence -1.
    EXPECT_NEAR(static_cast<double>(stats.data_packets),
                seconds * velodyne::PacketsPerSecond(model, ReturnMode::kStrongest) - 1.0, 1.0);
    EXPECT_NEAR(static_cast<double>(stats.position_packets),
                seconds * 1e6 / sim.options().position_period_us, 1.0);
    EXPECT_LE(max_step_error_ns, 1000) << "timestamps are whole microseconds";
    EXPECT_GT(stats.points, stats.data_packets * 300u) << "a closed room: almost every ray returns";
  }
}

TEST_F(LidarSimulatorTest, NoiselessPointsLieOnTheSceneWithinTheEncodingResolution) {
  for (const Model model : kModels) {
    SCOPED_TRACE(std::string(velodyne::ModelName(model)));
    LidarOptions options = Options(model);
    options.range_noise_sigma_m = 0.0;
    LidarSimulator sim = Make(options);
    const std::vector<WorldPoint> points = DecodeToWorld(sim, 400);
    ASSERT_GT(points.size(), 400u * 300u);
    // Rounding to the distance unit (half a unit) plus float decoding and the pose
    // interpolation (< 1 um here) stay below one unit.
    const double tolerance = sim.laser_table().distance_resolution_m;
    double worst = 0.0;
    for (const WorldPoint& p : points) worst = std::max(worst, scene_->DistanceToSurface(p.world, p.world_time_s));
    EXPECT_LT(worst, tolerance);
  }
}

TEST_F(LidarSimulatorTest, NoisyPointsLieWithinThreeSigma) {
  LidarOptions options = Options(Model::kHdl32e);
  options.range_noise_sigma_m = 0.02;
  LidarSimulator sim = Make(options);
  const std::vector<WorldPoint> points = DecodeToWorld(sim, 400);
  const double resolution = sim.laser_table().distance_resolution_m;
  int beyond_three_sigma = 0;
  double worst = 0.0;
  for (const WorldPoint& p : points) {
    const double d = scene_->DistanceToSurface(p.world, p.world_time_s);
    worst = std::max(worst, d);
    if (d > 3.0 * options.range_noise_sigma_m + resolution) ++beyond_three_sigma;
  }
  // 0.27 % of a normal lies beyond 3 sigma (fewer here: the distance to a surface is at most
  // the error along the ray); Box-Muller from 32-bit uniforms never exceeds 6.7 sigma.
  EXPECT_LT(beyond_three_sigma, static_cast<int>(0.005 * static_cast<double>(points.size())));
  EXPECT_LT(worst, 6.7 * options.range_noise_sigma_m + resolution);
  EXPECT_GT(worst, 2.0 * options.range_noise_sigma_m) << "the noise must be there";
}

TEST_F(LidarSimulatorTest, ReflectivityComesFromTheSurfaceHit) {
  LidarOptions options = Options(Model::kVlp16);
  LidarSimulator sim = Make(options);
  int on_cylinder_or_box = 0;
  for (const WorldPoint& p : DecodeToWorld(sim, 300)) {
    EXPECT_TRUE(p.intensity == 20 || p.intensity == 60 || p.intensity == 100 || p.intensity == 150)
        << int{p.intensity};
    if (p.intensity >= 100) ++on_cylinder_or_box;
  }
  EXPECT_GT(on_cylinder_or_box, 0);
}

TEST_F(LidarSimulatorTest, NothingAllocatesAfterCreate) {
  LidarSimulator sim = Make(Options(Model::kHdl32e));
  for (int i = 0; i < 3; ++i) sim.Next();  // warm up
  const std::uint64_t before = testing::AllocationCount();
  std::size_t bytes = 0;
  for (int i = 0; i < 500; ++i) bytes += sim.Next().payload.size();
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_GT(bytes, 500u * 512u);
}

TEST_F(LidarSimulatorTest, CreateRejectsInvalidOptionsNamingTheField) {
  const auto error_of = [&](const LidarOptions& options) {
    Result<LidarSimulator> sim = LidarSimulator::Create(*scene_, *trajectory_, options, 1);
    return sim.ok() ? std::string("accepted") : sim.error().message;
  };
  LidarOptions options = Options(Model::kVlp16);
  options.rotation_hz = 25.0;
  EXPECT_NE(error_of(options).find("rotation_hz"), std::string::npos);
  options = Options(Model::kVlp16);
  options.max_range_m = 200.0;  // 65535 x 2 mm = 131 m is the most a VLP-16 packet carries
  EXPECT_NE(error_of(options).find("max_range_m"), std::string::npos);
  options = Options(Model::kVlp16);
  options.dropout_probability = -0.1;
  EXPECT_NE(error_of(options).find("dropout_probability"), std::string::npos);
  options = Options(Model::kVlp16);
  options.laser_table = velodyne::DefaultLaserTable(Model::kHdl32e);
  EXPECT_NE(error_of(options).find("laser_table"), std::string::npos);
  options = Options(Model::kVlp32c);
  options.max_range_m = 200.0;
  EXPECT_EQ(error_of(options), "accepted");
}

}  // namespace
}  // namespace flat2d::hal::sim
