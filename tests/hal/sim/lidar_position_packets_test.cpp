// Position packets of the LiDAR simulator: they decode (position_packet.hpp) with the
// device time and the RMC time of the last PPS second, the GNSS fix is the truth within the
// configured noise (and has that noise), without GNSS the packets carry no sentence, and
// the sensor clock anchors on the fixes.
#include "hal/sim/lidar_position_packets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hal/sim/georeference.hpp"
#include "hal/velodyne/position_packet.hpp"
#include "hal/velodyne/sensor_clock.hpp"
#include "tests/hal/sim/lidar_simulator_fixture.hpp"

namespace flat2d::hal::sim {
namespace {

velodyne::PositionPacket DecodeOrFail(std::span<const std::uint8_t> payload) {
  Result<velodyne::PositionPacket> packet = velodyne::DecodePositionPacket(payload);
  EXPECT_TRUE(packet.ok()) << packet.error().message;
  return packet.ok() ? *packet : velodyne::PositionPacket{};
}

TimeNs RmcSecondOf(TimeNs device_ns, const GnssOptions& gnss) {
  const TimeNs latency_ns = std::llround(gnss.sentence_latency_s * 1e9);
  return (device_ns - latency_ns) / kNsPerSecond * kNsPerSecond;
}

TEST_F(LidarSimulatorTest, PositionPacketsCarryDeviceTimeAndANoisyFix) {
  LidarOptions options = Options(Model::kVlp16);
  options.gnss.enabled = true;
  options.gnss.horizontal_sigma_m = 0.5;
  LidarSimulator sim = Make(options);
  const int packets = static_cast<int>(2.5e6 / options.position_period_us);
  for (int i = 0; i < packets; ++i) {
    const SimulatedPacket& simulated = sim.NextPositionPacket();
    const velodyne::PositionPacket packet = DecodeOrFail(simulated.payload);
    EXPECT_EQ(packet.us_past_hour, static_cast<std::uint32_t>((simulated.device_time_ns % kNsPerHour) / kNsPerUs));
    EXPECT_EQ(packet.pps_status, velodyne::PpsStatus::kLocked);
    ASSERT_TRUE(packet.rmc.has_value());
    const velodyne::RmcFix& fix = *packet.rmc;
    ASSERT_TRUE(fix.valid && fix.has_position);
    EXPECT_EQ(fix.utc_time_ns, RmcSecondOf(simulated.device_time_ns, options.gnss));
    const VehicleState truth = trajectory_->At(sim.DriveTimeS(fix.utc_time_ns));
    const Eigen::Vector2d local = GeodeticToLocal(options.gnss.origin, {fix.latitude_deg, fix.longitude_deg});
    const Eigen::Vector2d error = local - truth.world_T_vehicle.translation().head<2>();
    // 4 sigma per axis (one in 16000 fixes) plus the sentence's 1e-7 minute (0.2 mm).
    EXPECT_LT(error.cwiseAbs().maxCoeff(), 4.0 * options.gnss.horizontal_sigma_m + 1e-3);
    EXPECT_NEAR(fix.speed_mps, truth.speed_mps, 0.001);
  }
}

TEST_F(LidarSimulatorTest, GnssFixesHaveTheConfiguredNoise) {
  LidarOptions options = Options(Model::kVlp16);
  options.gnss.enabled = true;
  options.gnss.horizontal_sigma_m = 2.0;
  const PositionPacketSimulator position(*trajectory_, options, 3);
  const int n = 600;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Vector2d sum_sq = Eigen::Vector2d::Zero();
  const std::int64_t first_second = options.start_epoch_ns / kNsPerSecond;
  for (int s = 0; s < n; ++s) {
    const velodyne::RmcFix fix = position.FixOfSecond(first_second + s);
    const Eigen::Vector2d local = GeodeticToLocal(options.gnss.origin, {fix.latitude_deg, fix.longitude_deg});
    const Eigen::Vector2d truth = trajectory_->At(s).world_T_vehicle.translation().head<2>();
    sum += local - truth;
    sum_sq += (local - truth).cwiseAbs2();
  }
  const double sigma = options.gnss.horizontal_sigma_m;
  for (int axis = 0; axis < 2; ++axis) {
    const double mean = sum[axis] / n;
    const double std_dev = std::sqrt(sum_sq[axis] / n - mean * mean);
    EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n));
    // The sample deviation of n normals has a relative spread of 1 / sqrt(2 n) = 2.9 %.
    EXPECT_NEAR(std_dev, sigma, 0.15 * sigma);
  }
}

// A survey receiver on the HDL-32E: centimetre fixes, written with seven decimals of minutes
// (the Garmin's four would round them to 18 cm).
TEST_F(LidarSimulatorTest, RtkFixesAreCentimetresAndWrittenToSevenDecimals) {
  LidarOptions options = Options(Model::kHdl32e);
  options.gnss.enabled = true;
  options.gnss.rtk = true;
  LidarSimulator sim = Make(options);
  double worst_m = 0.0;
  int fixes = 0;
  for (int i = 0; i < static_cast<int>(3e6 / options.position_period_us); ++i) {
    const SimulatedPacket& simulated = sim.NextPositionPacket();
    const velodyne::PositionPacket packet = DecodeOrFail(simulated.payload);
    ASSERT_TRUE(packet.rmc.has_value() && packet.rmc->has_position);
    const std::string sentence(packet.nmea_sentence());
    const std::size_t latitude = sentence.find(',', sentence.find(',', sentence.find(',') + 1) + 1) + 1;
    EXPECT_EQ(sentence.find(',', latitude) - sentence.find('.', latitude), 8u) << sentence;  // ".mmmmmmm"
    const velodyne::RmcFix& fix = *packet.rmc;
    const VehicleState truth = trajectory_->At(sim.DriveTimeS(fix.utc_time_ns));
    const Eigen::Vector2d local = GeodeticToLocal(options.gnss.origin, {fix.latitude_deg, fix.longitude_deg});
    worst_m = std::max(worst_m, (local - truth.world_T_vehicle.translation().head<2>()).cwiseAbs().maxCoeff());
    ++fixes;
  }
  EXPECT_GT(fixes, 100);
  EXPECT_GT(worst_m, 0.0);  // noisy...
  EXPECT_LT(worst_m, 4.0 * options.gnss.rtk_sigma_m + 1e-3);  // ... at 2 cm
}

TEST_F(LidarSimulatorTest, WithoutGnssPacketsCarryTheDeviceTimeAndNoSentence) {
  LidarOptions options = Options(Model::kVlp16);
  LidarSimulator sim = Make(options);
  velodyne::SensorClock clock;
  for (int i = 0; i < 200; ++i) {
    const SimulatedPacket& simulated = sim.NextPositionPacket();
    const velodyne::PositionPacket packet = DecodeOrFail(simulated.payload);
    EXPECT_EQ(packet.us_past_hour, static_cast<std::uint32_t>((simulated.device_time_ns % kNsPerHour) / kNsPerUs));
    EXPECT_EQ(packet.pps_status, velodyne::PpsStatus::kAbsent);
    EXPECT_FALSE(packet.rmc.has_value());
    EXPECT_EQ(packet.nmea_length, 0);
    clock.ObservePositionPacket(packet);
  }
  EXPECT_EQ(clock.source(), velodyne::TimeSource::kSensorOnly);
  // The receiver would still report void fixes with time and no position.
  const PositionPacketSimulator position(*trajectory_, options, 1);
  const velodyne::RmcFix fix = position.FixOfSecond(options.start_epoch_ns / kNsPerSecond + 7);
  EXPECT_EQ(fix.status, 'V');
  EXPECT_FALSE(fix.has_position);
  EXPECT_EQ(fix.utc_time_ns, options.start_epoch_ns + 7 * kNsPerSecond);
}

TEST_F(LidarSimulatorTest, TheSensorClockAnchorsOnTheFixAndResolvesDataTimes) {
  for (const Model model : kModels) {
    SCOPED_TRACE(std::string(velodyne::ModelName(model)));
    LidarOptions options = Options(model);
    options.gnss.enabled = true;
    LidarSimulator sim = Make(options);
    velodyne::SensorClock clock;
    int data_checked = 0;
    for (int i = 0; i < 2000; ++i) {
      const SimulatedPacket& simulated = sim.Next();
      if (simulated.kind == LidarPacketKind::kPosition) {
        const velodyne::PositionPacket packet = DecodeOrFail(simulated.payload);
        if (model == Model::kHdl32e) {
          // The HDL-32E capture's Garmin writes whole seconds ("$GPRMC,220243,A,...").
          EXPECT_EQ(packet.nmea_sentence().substr(13, 1), ",") << packet.nmea_sentence();
        }
        clock.ObservePositionPacket(packet);
      } else if (clock.source() == velodyne::TimeSource::kGps) {
        const std::uint32_t us = velodyne::ReadU32(simulated.payload.data() + velodyne::kTimestampOffset);
        EXPECT_EQ(clock.Resolve(us, 0), simulated.device_time_ns / kNsPerUs * kNsPerUs);
        ++data_checked;
      }
    }
    EXPECT_EQ(clock.source(), velodyne::TimeSource::kGps);
    EXPECT_GT(data_checked, 1000);
  }
}

}  // namespace
}  // namespace flat2d::hal::sim
