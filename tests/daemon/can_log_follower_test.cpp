// A candump log replayed on the LiDAR's clock (daemon/service/can_log_follower.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "daemon/service/can_log_follower.hpp"

namespace flat2d::daemon {
namespace {

// A 1206-byte data packet whose timestamp (offset 1200, little-endian) is `us_past_hour`.
std::vector<std::uint8_t> DataPacket(std::uint32_t us_past_hour) {
  std::vector<std::uint8_t> packet(1206, 0);
  for (int block = 0; block < 12; ++block) {
    packet[block * 100] = 0xFF;
    packet[block * 100 + 1] = 0xEE;
  }
  for (int i = 0; i < 4; ++i) packet[1200 + i] = static_cast<std::uint8_t>(us_past_hour >> (8 * i));
  packet[1204] = 0x37;
  packet[1205] = 0x22;
  return packet;
}

constexpr TimeNs kHour = 1767225600LL * kNsPerSecond;  // 2026-01-01T00:00:00Z, on the hour

TEST(CanLogFollower, DataPacketTimeResolvesTheHourFromTheReference) {
  EXPECT_EQ(DataPacketTime(DataPacket(1'500'000), kHour + 1'000'000'000), kHour + 1'500'000'000);
  // Just past the hour while the reference is just before it: the next hour.
  EXPECT_EQ(DataPacketTime(DataPacket(1'000), kHour - 2'000'000), kHour + 1'000'000);
  EXPECT_EQ(DataPacketTime(std::vector<std::uint8_t>(512, 0), kHour), 0);  // position packet
  std::vector<std::uint8_t> damaged = DataPacket(1'500'000);
  damaged[700] = 0x00;  // block 7's flag
  EXPECT_EQ(DataPacketTime(damaged, kHour), 0);
}

TEST(CanLogFollower, OneJumpingTimestampDoesNotRunTheLogAhead) {
  std::string log;
  for (int k = 0; k < 100; ++k) log += "(17672256" + std::to_string(10 + k / 10) + "." + std::to_string(k % 10) + "00000) can0 1D0#00\n";
  CanLogFollower follower(hal::can::CandumpReader::FromString(log));  // frames at 10.0 .. 19.9 s
  std::size_t released = 0;
  auto push = [&](const hal::can::CanFrame&) { ++released; };
  follower.ReleaseUntil(DataPacket(10'050'000), 0, push);  // 10.05 s: one frame
  EXPECT_EQ(released, 1u);
  follower.ReleaseUntil(DataPacket(18'000'000), 0, push);  // a damaged 18 s: ignored
  EXPECT_EQ(released, 1u);
  EXPECT_EQ(follower.implausible(), 1u);
  follower.ReleaseUntil(DataPacket(10'150'000), 0, push);  // the stream goes on at 10.15 s
  EXPECT_EQ(released, 2u);
  follower.ReleaseUntil(DataPacket(15'000'000), 0, push);  // a real jump (a pause), confirmed by the next
  EXPECT_EQ(released, 2u);
  follower.ReleaseUntil(DataPacket(15'100'000), 0, push);
  EXPECT_EQ(released, 52u);  // frames up to 15.1 s
}

TEST(CanLogFollower, ReleasesFramesUpToEachPacketsTime) {
  const std::string log =
      "(1767225601.000000) can0 1D0#0000000000000000\n"
      "(1767225601.010000) can0 1D0#0100000000000000\n"
      "(1767225601.020000) can0 1D0#0200000000000000\n"
      "(1767225601.030000) can0 1D0#0300000000000000\n";
  CanLogFollower follower(hal::can::CandumpReader::FromString(log));
  std::vector<TimeNs> released;
  auto push = [&](const hal::can::CanFrame& frame) { released.push_back(frame.time_ns); };
  follower.ReleaseUntil(DataPacket(1'005'000), 0, push);
  EXPECT_EQ(released, (std::vector<TimeNs>{kHour + 1'000'000'000}));
  follower.ReleaseUntil(std::vector<std::uint8_t>(512, 0), 0, push);  // position packets release nothing
  EXPECT_EQ(released.size(), 1u);
  follower.ReleaseUntil(DataPacket(1'020'000), 0, push);  // "not after": the frame at 1.020 s goes
  EXPECT_EQ(released.size(), 3u);
  EXPECT_FALSE(follower.finished());
  follower.ReleaseUntil(DataPacket(2'000'000), 0, push);
  EXPECT_EQ(released.size(), 4u);
  EXPECT_TRUE(follower.finished());
  EXPECT_EQ(follower.released(), 4u);
}

// LiDAR silence on a replayed drive: the log runs on at the rate the packets kept.
TEST(CanLogFollower, RunsThroughLidarSilenceAtTheReplaysRate) {
  std::string log;  // frames every 0.1 s from 10.0 to 29.9 s
  for (int k = 0; k < 200; ++k) log += "(17672256" + std::to_string(10 + k / 10) + "." + std::to_string(k % 10) + "00000) can0 1D0#00\n";
  CanLogFollower follower(hal::can::CandumpReader::FromString(log), /*run_through_silence=*/true);
  std::vector<TimeNs> released;
  auto push = [&](const hal::can::CanFrame& frame) { released.push_back(frame.time_ns); };
  // Packets every 0.1 s of sensor time arrive every 0.05 s of wall time: a replay at 2x.
  TimeNs wall = 1'000 * kNsPerSecond;
  for (int k = 0; k <= 60; ++k, wall += 50 * kNsPerMs) follower.ReleaseUntil(DataPacket(10'000'000 + k * 100'000), wall, push);
  EXPECT_NEAR(follower.rate(), 2.0, 1e-9);
  ASSERT_EQ(released.size(), 61u);  // up to 16.0 s
  const TimeNs last_wall = wall - 50 * kNsPerMs;
  follower.ReleaseThroughSilence(last_wall + 200 * kNsPerMs, push);  // not yet a silence
  EXPECT_EQ(released.size(), 61u);
  follower.ReleaseThroughSilence(last_wall + 2 * kNsPerSecond, push);  // 2 s of wall, 4 s of log
  EXPECT_EQ(released.size(), 101u);
  EXPECT_EQ(released.back(), kHour + 20 * kNsPerSecond);
  // The LiDAR returns at 23.0 s: a jump, confirmed by the next packet; no frame twice.
  follower.ReleaseUntil(DataPacket(23'000'000), last_wall + 3 * kNsPerSecond, push);
  follower.ReleaseUntil(DataPacket(23'100'000), last_wall + 3 * kNsPerSecond + 50 * kNsPerMs, push);
  EXPECT_EQ(released.size(), 132u);
  EXPECT_TRUE(std::is_sorted(released.begin(), released.end()));
  EXPECT_EQ(std::adjacent_find(released.begin(), released.end()), released.end());
}

TEST(CanLogFollower, WithoutRunThroughSilenceTheLogWaitsForTheLidar) {
  const std::string log = "(1767225601.000000) can0 1D0#00\n(1767225605.000000) can0 1D0#00\n";
  CanLogFollower follower(hal::can::CandumpReader::FromString(log));
  std::size_t released = 0;
  auto push = [&](const hal::can::CanFrame&) { ++released; };
  follower.ReleaseUntil(DataPacket(1'000'000), kNsPerSecond, push);
  follower.ReleaseThroughSilence(100 * kNsPerSecond, push);
  EXPECT_EQ(released, 1u);
}

}  // namespace
}  // namespace flat2d::daemon
