// Data packets of the LiDAR simulator: dropouts at the configured rate, range limits,
// rotation rates the revolution assembler sees as complete turns, dual return, and
// determinism (same seed, same bytes; any start, same packet).
#include "hal/sim/lidar_data_packets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "hal/net/udp_datagram.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "tests/hal/sim/lidar_simulator_fixture.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

TEST_F(LidarSimulatorTest, DropoutFractionMatchesTheProbability) {
  LidarOptions options = Options(Model::kHdl32e);
  options.range_noise_sigma_m = 0.0;
  LidarSimulator all = Make(options, 5);
  const auto returns_without = static_cast<double>(DecodeToWorld(all, 300).size());
  for (const double p : {0.05, 0.3}) {
    options.dropout_probability = p;
    LidarSimulator dropping = Make(options, 5);
    const auto returns_with = static_cast<double>(DecodeToWorld(dropping, 300).size());
    // Each ray is dropped independently: a binomial fraction, checked at 4 standard deviations.
    const double tolerance = 4.0 * std::sqrt(p * (1.0 - p) / returns_without);
    EXPECT_NEAR(1.0 - returns_with / returns_without, p, tolerance) << "p " << p;
  }
}

TEST_F(LidarSimulatorTest, ReturnsStayWithinTheRangeLimits) {
  LidarOptions options = Options(Model::kHdl32e);
  LidarSimulator unlimited_sim = Make(options);
  const std::size_t unlimited = DecodeToWorld(unlimited_sim, 200).size();
  options.min_range_m = 5.0;  // drops the lowest lasers' ground hits (3.7 m from 1.9 m up)
  options.max_range_m = 20.0;
  LidarSimulator sim = Make(options);
  const std::vector<WorldPoint> points = DecodeToWorld(sim, 200);
  const double resolution = sim.laser_table().distance_resolution_m;
  for (const WorldPoint& p : points) {
    ASSERT_GE(p.range_m, options.min_range_m - resolution);
    ASSERT_LE(p.range_m, options.max_range_m + resolution);
  }
  EXPECT_LT(points.size(), unlimited * 3 / 4) << "the room's walls lie beyond 20 m";
  EXPECT_GT(points.size(), unlimited / 10);
}

TEST_F(LidarSimulatorTest, RotationRateGivesCompleteRevolutionsOfTheRightSize) {
  for (const double hz : {5.0, 10.0, 20.0}) {
    SCOPED_TRACE(hz);
    LidarOptions options = Options(Model::kHdl32e);
    options.rotation_hz = hz;
    options.start_azimuth_deg = 123.0;
    LidarSimulator sim = Make(options);
    struct Turn {
      std::size_t fans;
      TimeNs start_ns, end_ns;
      double swept_rad;
    };
    std::vector<Turn> revolutions;
    velodyne::VelodyneStreamOptions stream_options;
    stream_options.model = Model::kHdl32e;
    velodyne::VelodyneStream stream(stream_options, [&](const velodyne::Revolution& revolution) {
      if (revolution.complete) {
        revolutions.push_back({revolution.fans.size(), revolution.start_ns(), revolution.end_ns(),
                               revolution.swept_azimuth_rad});
      }
    });
    const double seconds = 1.05;
    const double packets_per_turn = velodyne::PacketsPerSecond(Model::kHdl32e, ReturnMode::kStrongest) / hz;
    for (int i = 0; i < static_cast<int>(seconds * packets_per_turn * hz); ++i) {
      const SimulatedPacket& packet = sim.NextDataPacket();
      net::UdpDatagram datagram;
      datagram.receive_time_ns = packet.capture_time_ns;
      datagram.destination.port = packet.destination_port;
      datagram.payload = packet.payload;
      stream.Push(datagram);
    }
    EXPECT_GE(static_cast<double>(revolutions.size()), std::floor(seconds * hz) - 1.0);
    EXPECT_EQ(stream.stats().dropped_fans, 0u);
    for (const Turn& turn : revolutions) {
      // One fan per block: 12 fans per packet; a turn is a whole number of fans, +-1.
      EXPECT_NEAR(static_cast<double>(turn.fans), 12.0 * packets_per_turn, 1.0);
      EXPECT_NEAR(static_cast<double>(turn.end_ns - turn.start_ns) * 1e-9, 1.0 / hz,
                  2.0 * velodyne::TimingFor(Model::kHdl32e).block_period_us * 1e-6);
      EXPECT_NEAR(turn.swept_rad, kTwoPi, 2.0 * kTwoPi * hz * 46.08e-6);
    }
  }
}

TEST_F(LidarSimulatorTest, DualReturnRepeatsTheSingleSurfaceInBothBlocks) {
  LidarOptions options = Options(Model::kVlp16);
  options.return_mode = ReturnMode::kDual;
  options.range_noise_sigma_m = 0.0;
  LidarSimulator sim = Make(options);
  velodyne::PacketDecoder decoder(sim.laser_table());
  auto decoded = std::make_unique<velodyne::DecodedPacket>();
  for (int i = 0; i < 50; ++i) {
    decoder.Decode(sim.NextDataPacket().payload, *decoded);
    ASSERT_EQ(decoded->error, velodyne::PacketError::kNone);
    EXPECT_EQ(decoded->return_mode, ReturnMode::kDual);
    // Fans come as (last, strongest) pairs of one firing (firing_schedule.hpp).
    for (int f = 0; f + 1 < decoded->num_fans; f += 2) {
      const velodyne::Fan& last = decoded->fans[static_cast<std::size_t>(f)];
      const velodyne::Fan& strongest = decoded->fans[static_cast<std::size_t>(f + 1)];
      EXPECT_EQ(last.kind, velodyne::ReturnKind::kLast);
      EXPECT_EQ(last.stamp_ns, strongest.stamp_ns);
      for (int l = 0; l < 16; ++l) {
        EXPECT_EQ(last.returns[static_cast<std::size_t>(l)].range_m,
                  strongest.returns[static_cast<std::size_t>(l)].range_m);
      }
    }
  }
  LidarSimulator again = Make(options);
  const std::vector<WorldPoint> points = DecodeToWorld(again, 100);
  ASSERT_GT(points.size(), 100u * 300u);
  for (const WorldPoint& p : points) {
    ASSERT_LT(scene_->DistanceToSurface(p.world, p.world_time_s), sim.laser_table().distance_resolution_m);
  }
}

std::vector<std::vector<std::uint8_t>> Payloads(LidarSimulator& sim, int count) {
  std::vector<std::vector<std::uint8_t>> payloads;
  for (int i = 0; i < count; ++i) {
    const SimulatedPacket& packet = sim.Next();
    payloads.emplace_back(packet.payload.begin(), packet.payload.end());
  }
  return payloads;
}

TEST_F(LidarSimulatorTest, SameSeedSameBytesAndAnotherSeedOtherNoise) {
  LidarOptions options = Options(Model::kVlp32c);
  options.dropout_probability = 0.1;
  options.gnss.enabled = true;
  LidarSimulator first = Make(options, 42);
  LidarSimulator second = Make(options, 42);
  LidarSimulator other = Make(options, 43);
  const auto a = Payloads(first, 300);
  const auto b = Payloads(second, 300);
  const auto c = Payloads(other, 300);
  EXPECT_EQ(a, b);
  int differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differing += a[i] != c[i] ? 1 : 0;
  EXPECT_GT(differing, 250) << "every data packet carries noise";
}

TEST_F(LidarSimulatorTest, APacketDependsOnlyOnItsIndexNotOnTheStart) {
  LidarOptions options = Options(Model::kHdl32e);
  LidarSimulator from_start = Make(options, 9);
  std::vector<std::vector<std::uint8_t>> payloads;
  double drive_time_of_100th = 0.0;
  for (int i = 0; i < 150; ++i) {
    const SimulatedPacket& packet = from_start.NextDataPacket();
    if (i == 100) drive_time_of_100th = packet.drive_time_s;
    payloads.emplace_back(packet.payload.begin(), packet.payload.end());
  }
  options.start_drive_time_s = drive_time_of_100th;
  LidarSimulator later = Make(options, 9);
  for (int i = 100; i < 150; ++i) {
    const SimulatedPacket& packet = later.NextDataPacket();
    ASSERT_EQ(std::vector<std::uint8_t>(packet.payload.begin(), packet.payload.end()),
              payloads[static_cast<std::size_t>(i)])
        << "packet " << i;
  }
}

}  // namespace
}  // namespace flat2d::hal::sim
