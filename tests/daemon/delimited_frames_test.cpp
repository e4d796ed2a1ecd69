// Length-delimited framing of the API (daemon/api/delimited_frames.hpp): what protobuf's
// delimited streams write is what the reader cuts, however the bytes arrive, and a bad
// prefix or an oversized length is an error, never a buffer overrun.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>

#include "daemon/api/delimited_frames.hpp"
#include "daemon/api/flat2d_api.pb.h"

namespace flat2d::wire {
namespace {

namespace v1 = api::v1;

v1::Request PoseAt(std::uint64_t id, std::int64_t time_ns) {
  v1::Request request;
  request.set_id(id);
  request.mutable_pose_at()->set_time_ns(time_ns);
  return request;
}

// The bytes protobuf's own SerializeDelimitedToOstream-style writer produces.
std::string ProtobufDelimited(const std::vector<v1::Request>& requests) {
  std::string bytes;
  {
    google::protobuf::io::StringOutputStream stream(&bytes);  // flushes into `bytes` when it goes
    for (const auto& request : requests) {
      EXPECT_TRUE(google::protobuf::util::SerializeDelimitedToZeroCopyStream(request, &stream));
    }
  }
  return bytes;
}

void Feed(FrameReader& reader, const std::uint8_t* data, std::size_t size) {
  const std::span<std::uint8_t> space = reader.WritableSpace();
  ASSERT_LE(size, space.size());
  std::copy(data, data + size, space.begin());
  reader.Commit(size);
}

TEST(DelimitedFrames, VarintSizes) {
  EXPECT_EQ(VarintSize(0), 1u);
  EXPECT_EQ(VarintSize(127), 1u);
  EXPECT_EQ(VarintSize(128), 2u);
  EXPECT_EQ(VarintSize(16383), 2u);
  EXPECT_EQ(VarintSize(16384), 3u);
  EXPECT_EQ(VarintSize(0xFFFFFFFFu), 5u);
}

TEST(DelimitedFrames, WritesWhatProtobufWrites) {
  const std::vector<v1::Request> requests = {PoseAt(1, 1767225600123456789), PoseAt(300, -5)};
  std::vector<std::uint8_t> out(256);
  std::size_t used = 0;
  for (const auto& request : requests) {
    const auto next = AppendDelimited(request, 4096, out, used);
    ASSERT_TRUE(next.has_value());
    used = *next;
  }
  const std::string expected = ProtobufDelimited(requests);
  ASSERT_EQ(used, expected.size());
  std::string got(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(used));
  EXPECT_EQ(got, expected);
}

TEST(DelimitedFrames, ReadsFramesSplitAtEveryByteBoundary) {
  std::vector<v1::Request> requests;
  for (int i = 0; i < 20; ++i) requests.push_back(PoseAt(static_cast<std::uint64_t>(i) * 1000, i * 7919));
  v1::Request large;
  large.set_id(99);
  large.mutable_set_initial_pose()->mutable_global_t_vehicle()->set_x(1.5);
  requests.push_back(large);
  const std::string bytes = ProtobufDelimited(requests);
  std::mt19937 random(42);
  for (int trial = 0; trial < 50; ++trial) {
    FrameReader reader(256);
    std::vector<v1::Request> got;
    std::size_t offset = 0;
    while (offset < bytes.size()) {
      const std::size_t chunk = std::min<std::size_t>(bytes.size() - offset, 1 + random() % 17);
      Feed(reader, reinterpret_cast<const std::uint8_t*>(bytes.data()) + offset, chunk);
      offset += chunk;
      while (reader.Next() == FrameStatus::kFrame) {
        v1::Request request;
        ASSERT_TRUE(request.ParseFromArray(reader.frame().data(), static_cast<int>(reader.frame().size())));
        got.push_back(request);
      }
    }
    ASSERT_EQ(got.size(), requests.size()) << "trial " << trial;
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].SerializeAsString(), requests[i].SerializeAsString());
    EXPECT_EQ(reader.buffered(), 0u);
  }
}

TEST(DelimitedFrames, RejectsALengthAboveTheBound) {
  FrameReader reader(100);
  const std::uint8_t prefix[] = {0xC8, 0x01};  // 200
  Feed(reader, prefix, sizeof(prefix));
  EXPECT_EQ(reader.Next(), FrameStatus::kTooLarge);
}

TEST(DelimitedFrames, RejectsAPrefixLongerThanFiveBytes) {
  FrameReader reader(100);
  const std::uint8_t prefix[] = {0x80, 0x80, 0x80, 0x80, 0x80, 0x01};
  Feed(reader, prefix, 4);
  EXPECT_EQ(reader.Next(), FrameStatus::kNeedMore);
  Feed(reader, prefix + 4, 2);
  EXPECT_EQ(reader.Next(), FrameStatus::kBadPrefix);
}

TEST(DelimitedFrames, RejectsALengthAbove32Bits) {
  FrameReader reader(100);
  const std::uint8_t prefix[] = {0xFF, 0xFF, 0xFF, 0xFF, 0x7F};  // 2^35 - 1
  Feed(reader, prefix, sizeof(prefix));
  EXPECT_EQ(reader.Next(), FrameStatus::kBadPrefix);
}

TEST(DelimitedFrames, AZeroLengthFrameIsAnEmptyMessage) {
  FrameReader reader(100);
  const std::uint8_t empty[] = {0x00};
  Feed(reader, empty, 1);
  ASSERT_EQ(reader.Next(), FrameStatus::kFrame);
  EXPECT_TRUE(reader.frame().empty());
}

TEST(DelimitedFrames, AppendThatDoesNotFitLeavesTheBufferAlone) {
  const v1::Request request = PoseAt(7, 123456789);
  std::vector<std::uint8_t> out(request.ByteSizeLong(), 0xAB);  // one byte short for the prefix
  EXPECT_FALSE(AppendDelimited(request, 4096, out, 0).has_value());
  EXPECT_TRUE(std::all_of(out.begin(), out.end(), [](std::uint8_t b) { return b == 0xAB; }));
  std::vector<std::uint8_t> roomy(64);
  EXPECT_FALSE(AppendDelimited(request, request.ByteSizeLong() - 1, roomy, 0).has_value());  // above max_bytes
}

}  // namespace
}  // namespace flat2d::wire
