// The simulator's DBC: the embedded text is the file, it parses, its messages have the
// checksums, counters, byte orders and units the simulator and the shipped odometry
// configuration rely on, and frames built from it round-trip through CanOdometry's mapper.
#include "hal/sim/vehicle_dbc.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "hal/can/checksum.hpp"
#include "hal/can/message_encoder.hpp"
#include "hal/can/odometry_mapper.hpp"
#include "localization/odometry/can_odometry.hpp"
#include "localization/odometry/odometry_config.hpp"

namespace flat2d::hal::sim {
namespace {

const std::filesystem::path kSource = FLAT2D_SOURCE_DIR;

// fread rather than istreambuf_iterator: GCC 12 -O3 warns falsely about the latter.
std::string ReadFile(const std::filesystem::path& path) {
  std::string text(std::filesystem::file_size(path), '\0');
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return {};
  text.resize(std::fread(text.data(), 1, text.size(), file));
  std::fclose(file);
  return text;
}

localization::OdometryConfig ShippedConfig() {
  auto config = localization::LoadOdometryConfig(kSource / "packaging/config/odometry/flat2d_sim.textproto");
  EXPECT_TRUE(config.ok()) << (config.ok() ? "" : config.error().message);
  return config.ok() ? *config : localization::OdometryConfig{};
}

TEST(VehicleDbc, EmbeddedTextIsTheFile) {
  const std::string file = ReadFile(kSource / "hal/sim/vehicle.dbc");
  ASSERT_FALSE(file.empty());
  EXPECT_EQ(VehicleDbcText(), file);
}

TEST(VehicleDbc, ParsesWithTheMessagesTheSimulatorSends) {
  auto dbc = VehicleDbc();
  ASSERT_TRUE(dbc.ok()) << dbc.error().message;
  EXPECT_TRUE(dbc->warnings.empty());
  struct Expected {
    std::string_view name;
    std::uint32_t id;
    std::uint8_t dlc;
    can::ChecksumKind checksum;
    bool little_endian;
  };
  for (const Expected& e : {Expected{kWheelSpeedsMessage, 0x1A0, 8, can::ChecksumKind::kHonda, false},
                            Expected{kYawRateMessage, 0xB0, 8, can::ChecksumKind::kToyota, true},
                            Expected{kSteeringMessage, 0x25, 5, can::ChecksumKind::kToyota, false}}) {
    SCOPED_TRACE(std::string(e.name));
    const can::DbcMessage* message = dbc->FindMessage(e.name);
    ASSERT_NE(message, nullptr);
    EXPECT_EQ(message->id, e.id);
    EXPECT_FALSE(message->extended);
    EXPECT_EQ(message->dlc, e.dlc);
    EXPECT_FALSE(message->transmitter.empty());
    EXPECT_FALSE(message->comment.empty());
    EXPECT_EQ(can::DetectChecksum(*message), e.checksum);
    ASSERT_NE(message->FindSignal("COUNTER"), nullptr);
    EXPECT_EQ(message->FindSignal("COUNTER")->length, 4);
    for (const can::DbcSignal& signal : message->signals) {
      EXPECT_EQ(signal.little_endian, e.little_endian) << signal.name;
      EXPECT_FALSE(signal.comment.empty()) << signal.name;
    }
  }
  const can::DbcSignal* yaw = dbc->FindMessage(kYawRateMessage)->FindSignal("YAW_RATE");
  ASSERT_NE(yaw, nullptr);
  EXPECT_TRUE(yaw->is_signed);
  EXPECT_EQ(yaw->unit, "deg/s");
  EXPECT_LE(yaw->factor, 0.01);  // fine enough that quantization cannot hide a MEMS bias
}

TEST(VehicleDbc, ShippedConfigurationBuildsCanOdometry) {
  auto dbc = VehicleDbc();
  ASSERT_TRUE(dbc.ok());
  auto odometry = localization::CanOdometry::Create(*dbc, ShippedConfig());
  EXPECT_TRUE(odometry.ok()) << (odometry.ok() ? "" : odometry.error().message);
}

// Values encoded with MessageEncoder come back through the shipped mapping in SI units,
// within half a resolution step, with verified checksums.
TEST(VehicleDbc, EncodedFramesMapBackToSiUnits) {
  auto dbc = VehicleDbc();
  ASSERT_TRUE(dbc.ok());
  auto mapper = can::OdometryMapper::Create(*dbc, ShippedConfig().mapping());
  ASSERT_TRUE(mapper.ok()) << mapper.error().message;
  auto wheels = can::MessageEncoder::Create(*dbc, kWheelSpeedsMessage);
  auto yaw = can::MessageEncoder::Create(*dbc, kYawRateMessage);
  auto steering = can::MessageEncoder::Create(*dbc, kSteeringMessage);
  ASSERT_TRUE(wheels.ok() && yaw.ok() && steering.ok());
  const double kph = 1.0 / 3.6, deg = 3.14159265358979323846 / 180.0;
  const std::array<double, 4> speeds_kph = {36.013, 35.9, 120.553, 0.0};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(wheels->Set(std::array{"WHEEL_SPEED_FL", "WHEEL_SPEED_FR", "WHEEL_SPEED_RL", "WHEEL_SPEED_RR"}[i],
                          speeds_kph[i]),
              can::EncodeStatus::kOk);
  }
  can::OdometryMeasurement m;
  ASSERT_TRUE(mapper->Map(wheels->Build(1000), m));
  ASSERT_TRUE(m.wheel_speeds.has_value());
  EXPECT_NEAR(m.wheel_speeds->front_left_mps, speeds_kph[0] * kph, 0.01 * kph);
  EXPECT_NEAR(m.wheel_speeds->front_right_mps, speeds_kph[1] * kph, 0.01 * kph);
  EXPECT_NEAR(m.wheel_speeds->rear_left_mps, speeds_kph[2] * kph, 0.01 * kph);
  EXPECT_EQ(m.wheel_speeds->rear_right_mps, 0.0);

  EXPECT_EQ(yaw->Set("YAW_RATE", -37.12345), can::EncodeStatus::kOk);
  ASSERT_TRUE(mapper->Map(yaw->Build(2000), m));
  ASSERT_TRUE(m.yaw_rate_radps.has_value());
  EXPECT_NEAR(*m.yaw_rate_radps, -37.12345 * deg, 0.0001 * deg);

  EXPECT_EQ(steering->Set("STEER_ANGLE", -123.46), can::EncodeStatus::kOk);
  ASSERT_TRUE(mapper->Map(steering->Build(3000), m));
  ASSERT_TRUE(m.steering_angle_rad.has_value());
  EXPECT_NEAR(*m.steering_angle_rad, -123.46 * deg / 15.0, 0.025 * deg / 15.0);  // road-wheel angle

  EXPECT_EQ(mapper->decoder_stats().checksum_checked, 3u);
  EXPECT_EQ(mapper->decoder_stats().checksum_failures, 0u);
}

}  // namespace
}  // namespace flat2d::hal::sim
