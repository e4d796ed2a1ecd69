// The real DBCs and logs of ../shared/data/can (PROVENANCE.md, section can/): the three
// DBCs load with the definitions PROVENANCE gives; checksums verify on every frame that
// carries one; our decode of the RAV4's wheel speeds and steering angle equals comma's own
// decode of the same frames (comma2k19 processed_log). Skips when the data is absent.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/can/checksum.hpp"
#include "hal/can/dbc.hpp"
#include "hal/can/frame_decoder.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::can {
namespace {

constexpr const char* kRav4Dbc = "can/toyota_rav4h_comma2k19/toyota_rav4_hybrid_2017_pt_generated.dbc";
constexpr const char* kRav4Log = "can/toyota_rav4h_comma2k19/DERIVED_comma2k19_rav4h_seg40_bus0.candump.log";
constexpr const char* kCommaCan =
    "can/toyota_rav4h_comma2k19/b0c9d2329ad1606b_2018-08-02--08-34-47_seg40/processed_log/CAN/";
constexpr const char* kStrymDbc = "can/toyota_verifiedcan/strym_toyota_rav4_2019.dbc";
constexpr const char* kStrymLog =
    "can/toyota_verifiedcan/DERIVED_verifiedcan_toyota_2020-02-03-14-31-11.candump.log";
constexpr const char* kHondaDbc = "can/eldominio_candump/honda_civic_hatchback_ex_2017_can_generated.dbc";
constexpr const char* kHondaLog = "can/eldominio_candump/civic_19_type_r__turnonanddrive.log";

Dbc Load(const std::filesystem::path& path) {
  auto dbc = LoadDbc(path);
  EXPECT_TRUE(dbc.ok()) << (dbc.ok() ? "" : dbc.error().message);
  return dbc.ok() ? std::move(*dbc) : Dbc{};
}

// "(seconds.micros) iface ID#HEX" only: the real candump reader lives elsewhere.
std::vector<CanFrame> ReadCandump(const std::filesystem::path& path) {
  std::vector<CanFrame> frames;
  std::ifstream file(path);
  std::string time, iface, body;
  while (file >> time >> iface >> body) {
    const std::size_t hash = body.find('#');
    CanFrame frame;
    frame.time_ns = static_cast<TimeNs>(std::stod(time.substr(1)) * 1e9 + 0.5);
    frame.id = static_cast<std::uint32_t>(std::stoul(body.substr(0, hash), nullptr, 16));
    frame.extended = hash > 3;
    const std::string hex = body.substr(hash + 1);
    frame.length = static_cast<std::uint8_t>(hex.size() / 2);
    for (std::size_t i = 0; i < frame.length; ++i) {
      frame.data[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
    }
    frame.set_interface_name(iface);
    frames.push_back(frame);
  }
  return frames;
}

// The doubles of a NumPy v1 '<f8' array file (header: magic, version, u16 length, dict).
std::vector<double> ReadNpyDoubles(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream contents;
  contents << file.rdbuf();
  const std::string bytes = contents.str();
  if (bytes.size() < 10) {
    ADD_FAILURE() << path << " is too short for a NumPy file";
    return {};
  }
  EXPECT_EQ(bytes.substr(1, 5), "NUMPY");
  EXPECT_NE(bytes.find("'<f8'"), std::string::npos);
  const std::size_t header_length =
      static_cast<std::uint8_t>(bytes[8]) + 256u * static_cast<std::uint8_t>(bytes[9]);
  const std::size_t header = std::min(bytes.size(), 10 + header_length);
  std::vector<double> values((bytes.size() - header) / sizeof(double));
  std::memcpy(values.data(), bytes.data() + header, values.size() * sizeof(double));
  return values;
}

void ExpectSignal(const Dbc& dbc, const char* message, std::uint32_t id, const char* name, std::uint16_t start,
                  std::uint8_t length, bool is_signed, double factor, double offset, const char* unit) {
  const DbcMessage* by_id = dbc.FindMessage(id, false);
  ASSERT_NE(by_id, nullptr) << message;
  EXPECT_EQ(by_id->name, message);
  const DbcSignal* signal = by_id->FindSignal(name);
  ASSERT_NE(signal, nullptr) << name;
  EXPECT_EQ(signal->start_bit, start) << name;
  EXPECT_EQ(signal->length, length) << name;
  EXPECT_FALSE(signal->little_endian) << name;
  EXPECT_EQ(signal->is_signed, is_signed) << name;
  EXPECT_DOUBLE_EQ(signal->factor, factor) << name;
  EXPECT_DOUBLE_EQ(signal->offset, offset) << name;
  EXPECT_EQ(signal->unit, unit) << name;
}

// opendbc's file writes speeds in "km/h", strym's copy in "kph".
void ExpectToyotaOdometrySignals(const Dbc& dbc, const char* speed_unit) {
  for (const char* wheel : {"WHEEL_SPEED_FR", "WHEEL_SPEED_FL", "WHEEL_SPEED_RR", "WHEEL_SPEED_RL"}) {
    const std::uint16_t start = wheel[12] == 'F' ? (wheel[13] == 'R' ? 7 : 23) : (wheel[13] == 'R' ? 39 : 55);
    ExpectSignal(dbc, "WHEEL_SPEEDS", 0xAA, wheel, start, 16, false, 0.01, -67.67, speed_unit);
  }
  ExpectSignal(dbc, "SPEED", 0xB4, "SPEED", 47, 16, false, 0.01, 0.0, speed_unit);
  ExpectSignal(dbc, "KINEMATICS", 0x24, "YAW_RATE", 1, 10, false, 0.244, -125.0, "deg/s");
  ExpectSignal(dbc, "KINEMATICS", 0x24, "ACCEL_Y", 33, 10, false, 0.03589, -18.375, "m/s^2");
  ExpectSignal(dbc, "STEER_ANGLE_SENSOR", 0x25, "STEER_ANGLE", 3, 12, true, 1.5, 0.0, "deg");
  ExpectSignal(dbc, "STEER_ANGLE_SENSOR", 0x25, "STEER_FRACTION", 39, 4, true, 0.1, 0.0, "deg");
}

TEST(DbcRealDataTest, Rav4HybridDbcHasProvenanceDefinitions) {
  FLAT2D_REQUIRE_DATA(path, kRav4Dbc);
  const Dbc dbc = Load(path);
  EXPECT_EQ(dbc.messages.size(), 47u);
  ExpectToyotaOdometrySignals(dbc, "km/h");
  EXPECT_EQ(dbc.FindMessage(0x24, false)->FindSignal("YAW_RATE")->comment, "verify");
  EXPECT_TRUE(dbc.warnings.empty());
}

TEST(DbcRealDataTest, StrymRav4DbcHasProvenanceDefinitionsAndMultiplexing) {
  FLAT2D_REQUIRE_DATA(path, kStrymDbc);
  const Dbc dbc = Load(path);
  EXPECT_EQ(dbc.messages.size(), 96u);
  ExpectToyotaOdometrySignals(dbc, "kph");
  ExpectSignal(dbc, "KINEMATICS", 0x24, "ACCEL_X", 17, 10, false, 0.03589, -18.375, "m/s^2");
  const DbcMessage* track = dbc.FindMessage("TRACK_B_1");
  ASSERT_NE(track, nullptr);
  ASSERT_NE(track->MultiplexSwitch(), nullptr);
  EXPECT_EQ(track->MultiplexSwitch()->name, "TRACKB1_mux");
}

TEST(DbcRealDataTest, HondaCivicDbcHasProvenanceDefinitions) {
  FLAT2D_REQUIRE_DATA(path, kHondaDbc);
  const Dbc dbc = Load(path);
  EXPECT_EQ(dbc.messages.size(), 50u);
  ExpectSignal(dbc, "WHEEL_SPEEDS", 0x1D0, "WHEEL_SPEED_FL", 7, 15, false, 0.01, 0.0, "kph");
  ExpectSignal(dbc, "WHEEL_SPEEDS", 0x1D0, "WHEEL_SPEED_FR", 8, 15, false, 0.01, 0.0, "kph");
  ExpectSignal(dbc, "WHEEL_SPEEDS", 0x1D0, "WHEEL_SPEED_RL", 25, 15, false, 0.01, 0.0, "kph");
  ExpectSignal(dbc, "WHEEL_SPEEDS", 0x1D0, "WHEEL_SPEED_RR", 42, 15, false, 0.01, 0.0, "kph");
  ExpectSignal(dbc, "ENGINE_DATA", 0x158, "XMISSION_SPEED", 7, 16, false, 0.01, 0.0, "kph");
  ExpectSignal(dbc, "STEERING_SENSORS", 0x14A, "STEER_ANGLE", 7, 16, true, -0.1, 0.0, "deg");
  EXPECT_EQ(dbc.warnings.size(), 2u);  // LKAS_HUD_A/B: 29-bit ids without bit 31
}

// Toyota checksum on the RAV4 log: 0xB4 names CHECKSUM in the DBC (detected); 0x24 and
// 0x25 carry one that the DBC does not name (configured).
ChecksumOptions Rav4Checksums() {
  ChecksumOptions options;
  options.overrides = {{"KINEMATICS", ChecksumKind::kToyota}, {"STEER_ANGLE_SENSOR", ChecksumKind::kToyota}};
  return options;
}

const std::vector<SignalSelection> kToyotaSelection = {
    {"KINEMATICS", "YAW_RATE"}, {"STEER_ANGLE_SENSOR", "STEER_ANGLE"}, {"SPEED", "SPEED"}};

TEST(DbcRealDataTest, ToyotaChecksumHoldsOnEveryRav4Frame) {
  FLAT2D_REQUIRE_DATA(dbc_path, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log_path, kRav4Log);
  const Dbc dbc = Load(dbc_path);
  auto decoder = FrameDecoder::Create(dbc, kToyotaSelection, Rav4Checksums());
  ASSERT_TRUE(decoder.ok()) << decoder.error().message;
  const std::vector<CanFrame> frames = ReadCandump(log_path);
  ASSERT_EQ(frames.size(), 53800u);
  std::map<std::uint32_t, int> checked;
  int flipped_failures = 0;
  for (const CanFrame& frame : frames) {
    if (decoder->Decode(frame) == FrameStatus::kIgnored) continue;
    ++checked[frame.id];
    // One flipped bit, a different one each frame, must fail.
    CanFrame corrupted = frame;
    const std::size_t bit = static_cast<std::size_t>(checked[frame.id]) % 64;
    corrupted.data[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    flipped_failures += VerifyChecksum(ChecksumKind::kToyota, corrupted) ? 0 : 1;
  }
  EXPECT_EQ(checked[0x24], 4974);
  EXPECT_EQ(checked[0x25], 4974);
  EXPECT_EQ(checked[0xB4], 2487);
  EXPECT_EQ(decoder->stats().checksum_checked, 12435u);
  EXPECT_EQ(decoder->stats().checksum_failures, 0u);
  EXPECT_EQ(decoder->stats().too_short, 0u);
  EXPECT_EQ(flipped_failures, 12435);
}

TEST(DbcRealDataTest, ToyotaChecksumHoldsOnTheVerifiedCanLogWithStrymDbc) {
  FLAT2D_REQUIRE_DATA(dbc_path, kStrymDbc);
  FLAT2D_REQUIRE_DATA(log_path, kStrymLog);
  const Dbc dbc = Load(dbc_path);
  auto decoder = FrameDecoder::Create(dbc, AllSignals(dbc), Rav4Checksums());
  ASSERT_TRUE(decoder.ok()) << decoder.error().message;
  for (const CanFrame& frame : ReadCandump(log_path)) {
    if (frame.interface_name() == "can0") decoder->Decode(frame);  // the DBC's bus
  }
  // Every message with a CHECKSUM signal is checked, TRACK_B_1 (multiplexed) included.
  EXPECT_EQ(decoder->stats().checksum_checked, 16997u);  // 0x24, 0x25, 0xB4: 5432 of them
  EXPECT_EQ(decoder->stats().checksum_failures, 0u);
  EXPECT_EQ(decoder->stats().too_short, 0u);
}

// comma2k19's wheel_speed/value is 4974 x 4 m/s in the order FL, FR, RL, RR, one row per
// 0xAA frame: equal to our km/h / 3.6 up to float rounding.
TEST(DbcRealDataTest, Rav4WheelSpeedsEqualCommasDecode) {
  FLAT2D_REQUIRE_DATA(dbc_path, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log_path, kRav4Log);
  FLAT2D_REQUIRE_DATA(comma_path, std::string(kCommaCan) + "wheel_speed/value");
  const std::vector<SignalSelection> wheels = {{"WHEEL_SPEEDS", "WHEEL_SPEED_FL"},
                                               {"WHEEL_SPEEDS", "WHEEL_SPEED_FR"},
                                               {"WHEEL_SPEEDS", "WHEEL_SPEED_RL"},
                                               {"WHEEL_SPEEDS", "WHEEL_SPEED_RR"}};
  auto decoder = FrameDecoder::Create(Load(dbc_path), wheels);
  ASSERT_TRUE(decoder.ok()) << decoder.error().message;
  const std::vector<double> comma = ReadNpyDoubles(comma_path);
  ASSERT_EQ(comma.size(), 4974u * 4);
  std::size_t row = 0;
  double max_error = 0.0;
  for (const CanFrame& frame : ReadCandump(log_path)) {
    if (decoder->Decode(frame) != FrameStatus::kDecoded) continue;
    ASSERT_LT(row, 4974u);
    for (std::size_t wheel = 0; wheel < 4; ++wheel) {
      max_error = std::max(max_error, std::abs(decoder->values()[wheel].value / 3.6 - comma[4 * row + wheel]));
    }
    ++row;
  }
  EXPECT_EQ(row, 4974u);
  EXPECT_LT(max_error, 1e-9) << "max |ours - comma| in m/s";
}

// comma's steering_angle is STEER_ANGLE + STEER_FRACTION (signed Motorola, 12 and 4 bits).
TEST(DbcRealDataTest, Rav4SteeringEqualsCommasDecode) {
  FLAT2D_REQUIRE_DATA(dbc_path, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log_path, kRav4Log);
  FLAT2D_REQUIRE_DATA(comma_path, std::string(kCommaCan) + "steering_angle/value");
  auto decoder = FrameDecoder::Create(
      Load(dbc_path), std::vector<SignalSelection>{{"STEER_ANGLE_SENSOR", "STEER_ANGLE"},
                                                   {"STEER_ANGLE_SENSOR", "STEER_FRACTION"}});
  ASSERT_TRUE(decoder.ok()) << decoder.error().message;
  const std::vector<double> comma = ReadNpyDoubles(comma_path);
  ASSERT_EQ(comma.size(), 4974u);
  std::size_t row = 0;
  double max_error = 0.0;
  double minimum = 0.0;
  double maximum = 0.0;
  for (const CanFrame& frame : ReadCandump(log_path)) {
    if (decoder->Decode(frame) != FrameStatus::kDecoded) continue;
    ASSERT_LT(row, comma.size());
    const double angle = decoder->values()[0].value + decoder->values()[1].value;
    max_error = std::max(max_error, std::abs(angle - comma[row++]));
    minimum = std::min(minimum, decoder->values()[0].value);
    maximum = std::max(maximum, decoder->values()[0].value);
  }
  EXPECT_EQ(row, 4974u);
  EXPECT_LT(max_error, 1e-9);
  EXPECT_DOUBLE_EQ(minimum, -4.5);  // PROVENANCE: STEER_ANGLE -4.5..+3.0 deg
  EXPECT_DOUBLE_EQ(maximum, 3.0);
}

// Honda's nibble checksum holds on every Civic frame whose DBC message has one, except
// ROUGH_WHEEL_SPEED (0x255): this 2019 Type R sends it with all eight bytes summing to 0
// mod 256 instead (the DBC is the 2017 hatchback's). Wheel speeds: PROVENANCE's 0..9.6.
TEST(DbcRealDataTest, HondaChecksumHoldsOnCivicFramesExceptRoughWheelSpeed) {
  FLAT2D_REQUIRE_DATA(dbc_path, kHondaDbc);
  FLAT2D_REQUIRE_DATA(log_path, kHondaLog);
  const Dbc dbc = Load(dbc_path);
  std::map<std::uint32_t, std::pair<int, int>> results;  // id -> (checked, failed)
  for (const CanFrame& frame : ReadCandump(log_path)) {
    const DbcMessage* message = dbc.FindMessage(frame.id, frame.extended);
    if (message == nullptr || DetectChecksum(*message) != ChecksumKind::kHonda) continue;
    auto& [checked, failed] = results[frame.id];
    ++checked;
    failed += VerifyChecksum(ChecksumKind::kHonda, frame) ? 0 : 1;
  }
  EXPECT_EQ(results.size(), 22u);
  EXPECT_EQ(results[0x1D0].first, 803);
  for (const auto& [id, counts] : results) {
    if (id == 0x255) continue;
    EXPECT_EQ(counts.second, 0) << "id 0x" << std::hex << id << std::dec << " failed " << counts.second
                                << " of " << counts.first;
  }
  EXPECT_GT(results[0x255].second, results[0x255].first / 2);

  auto decoder = FrameDecoder::Create(dbc, std::vector<SignalSelection>{{"WHEEL_SPEEDS", "WHEEL_SPEED_FL"},
                                                                        {"WHEEL_SPEEDS", "WHEEL_SPEED_FR"},
                                                                        {"WHEEL_SPEEDS", "WHEEL_SPEED_RL"},
                                                                        {"WHEEL_SPEEDS", "WHEEL_SPEED_RR"}});
  ASSERT_TRUE(decoder.ok()) << decoder.error().message;
  double maximum = 0.0;
  for (const CanFrame& frame : ReadCandump(log_path)) {
    if (decoder->Decode(frame) != FrameStatus::kDecoded) continue;
    for (const DecodedSignal& value : decoder->values()) {
      EXPECT_GE(value.value, 0.0);
      maximum = std::max(maximum, value.value);
    }
  }
  EXPECT_EQ(decoder->stats().decoded, 803u);
  EXPECT_EQ(decoder->stats().checksum_failures, 0u);
  EXPECT_NEAR(maximum, 9.56, 0.005);
}

}  // namespace
}  // namespace flat2d::hal::can
