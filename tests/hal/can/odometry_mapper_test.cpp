#include "hal/can/odometry_mapper.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "hal/can/checksum.hpp"
#include "hal/config/text_proto.hpp"

namespace flat2d::hal::can {
namespace {

// A small DBC: wheel speeds in one message (Motorola, as Toyota's), yaw rate in another.
constexpr char kDbc[] = R"(VERSION ""
BO_ 170 WHEEL_SPEEDS: 8 XXX
 SG_ WHEEL_SPEED_FR : 7|16@0+ (0.01,-67.67) [0|250] "km/h" XXX
 SG_ WHEEL_SPEED_FL : 23|16@0+ (0.01,-67.67) [0|250] "km/h" XXX
 SG_ WHEEL_SPEED_RR : 39|16@0+ (0.01,-67.67) [0|250] "km/h" XXX
 SG_ WHEEL_SPEED_RL : 55|16@0+ (0.01,-67.67) [0|250] "km/h" XXX
BO_ 36 KINEMATICS: 8 XXX
 SG_ YAW_RATE : 1|10@0+ (0.244,-125) [0|65535] "deg/s" XXX
)";

OdometryMapping ParseMapping(const char* text) {
  OdometryMapping mapping;
  const Status status = config::ParseTextProto(text, "mapping", mapping);
  EXPECT_TRUE(status.ok()) << status.error().message;
  return mapping;
}

constexpr char kMapping[] = R"(
  wheel_speed_front_left { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_FL" unit: "km/h" }
  wheel_speed_front_right { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_FR" unit: "km/h" }
  wheel_speed_rear_left { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_RL" unit: "km/h" }
  wheel_speed_rear_right { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_RR" unit: "km/h" scale: 1.01 }
  yaw_rate { message: "KINEMATICS" signal: "YAW_RATE" unit: "deg/s" }
  checksum: CHECKSUM_NONE
)";

CanFrame Frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes, TimeNs time) {
  CanFrame frame;
  frame.id = id;
  frame.time_ns = time;
  frame.length = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), frame.data.begin());
  return frame;
}

TEST(OdometryMapper, ConvertsHandBuiltFramesToSi) {
  auto dbc = ParseDbc(kDbc, "test.dbc");
  ASSERT_TRUE(dbc.ok()) << dbc.error().message;
  auto mapper = OdometryMapper::Create(*dbc, ParseMapping(kMapping));
  ASSERT_TRUE(mapper.ok()) << mapper.error().message;

  // Raw 0x2000 = 8192: 81.92 - 67.67 = 14.25 km/h = 3.958333 m/s on every wheel.
  OdometryMeasurement out;
  ASSERT_TRUE(mapper->Map(Frame(170, {0x20, 0x00, 0x20, 0x00, 0x20, 0x00, 0x20, 0x00}, 5), out));
  EXPECT_EQ(out.time_ns, 5);
  ASSERT_TRUE(out.wheel_speeds.has_value());
  EXPECT_NEAR(out.wheel_speeds->front_left_mps, 14.25 / 3.6, 1e-12);
  EXPECT_NEAR(out.wheel_speeds->rear_right_mps, 1.01 * 14.25 / 3.6, 1e-12);  // configured scale
  EXPECT_FALSE(out.yaw_rate_radps.has_value());

  // YAW_RATE 1|10@0+: raw bits 1..0 of byte 0 then byte 1. Raw 0x21C = 540:
  // 540 x 0.244 - 125 = 6.76 deg/s.
  ASSERT_TRUE(mapper->Map(Frame(36, {0x02, 0x1C, 0, 0, 0, 0, 0, 0}, 7), out));
  ASSERT_TRUE(out.yaw_rate_radps.has_value());
  EXPECT_NEAR(*out.yaw_rate_radps, 6.76 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_FALSE(out.wheel_speeds.has_value());

  EXPECT_FALSE(mapper->Map(Frame(0x123, {1, 2, 3}, 9), out));  // not mapped
  EXPECT_EQ(mapper->stats().measurements, 2u);
}

TEST(OdometryMapper, ChecksumFailuresDropTheFrame) {
  auto dbc = ParseDbc(kDbc, "test.dbc");
  ASSERT_TRUE(dbc.ok());
  auto mapper = OdometryMapper::Create(*dbc, ParseMapping(R"(
      vehicle_speed { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_FL" unit: "km/h" }
      yaw_rate { message: "KINEMATICS" signal: "YAW_RATE" unit: "deg/s" checksum: CHECKSUM_TOYOTA })"));
  ASSERT_TRUE(mapper.ok()) << mapper.error().message;
  CanFrame frame = Frame(36, {0x02, 0x1C, 0, 0, 0, 0, 0, 0}, 1);
  frame.data[7] = ToyotaChecksum(36, frame.payload());
  OdometryMeasurement out;
  EXPECT_TRUE(mapper->Map(frame, out));
  frame.data[1] ^= 0x10;  // one flipped bit
  EXPECT_FALSE(mapper->Map(frame, out));
  EXPECT_EQ(mapper->decoder_stats().checksum_failures, 1u);
}

TEST(OdometryMapper, ConfigurationErrorsNameTheField) {
  auto dbc = ParseDbc(kDbc, "test.dbc");
  ASSERT_TRUE(dbc.ok());
  auto error_of = [&](const char* text) {
    auto mapper = OdometryMapper::Create(*dbc, ParseMapping(text));
    return mapper.ok() ? std::string("ok") : mapper.error().message;
  };
  EXPECT_NE(error_of(R"(vehicle_speed { message: "SPEED" signal: "SPEED" unit: "km/h" })")
                .find("vehicle_speed: no message 'SPEED'"), std::string::npos);
  EXPECT_NE(error_of(R"(vehicle_speed { message: "WHEEL_SPEEDS" signal: "X" unit: "km/h" })")
                .find("has no signal 'X'"), std::string::npos);
  EXPECT_NE(error_of(R"(vehicle_speed { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_FL" unit: "deg/s" })")
                .find("is not a speed unit"), std::string::npos);
  EXPECT_NE(error_of(R"(vehicle_speed { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_FL" unit: "m/s" })")
                .find("disagrees with the DBC's 'km/h'"), std::string::npos);
  EXPECT_NE(error_of(R"(wheel_speed_front_left { message: "WHEEL_SPEEDS" signal: "WHEEL_SPEED_FL" unit: "km/h" })")
                .find("all four wheel speeds"), std::string::npos);
  EXPECT_NE(error_of(R"(yaw_rate { message: "KINEMATICS" signal: "YAW_RATE" unit: "deg/s" })")
                .find("map the wheel speeds or vehicle_speed"), std::string::npos);
}

}  // namespace
}  // namespace flat2d::hal::can
