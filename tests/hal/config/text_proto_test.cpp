#include "hal/config/text_proto.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/hal/config/text_proto_test.pb.h"

namespace flat2d::hal::config {
namespace {

using Sample = test::Sample;

TEST(TextProto, ParsesNestedRepeatedEnumAndOptionalFields) {
  Sample sample;
  const Status status = ParseTextProto(R"(
      # comments are allowed
      rate_hz: 12.5
      mode: MODE_FAST
      items { name: "a" value: 1 }
      items { name: "b" value: -2.5 }
      count: 7
  )", "sample.textproto", sample);
  ASSERT_TRUE(status.ok()) << status.error().message;
  ASSERT_TRUE(sample.has_rate_hz());
  EXPECT_DOUBLE_EQ(sample.rate_hz(), 12.5);
  EXPECT_EQ(sample.mode(), Sample::MODE_FAST);
  ASSERT_EQ(sample.items_size(), 2);
  EXPECT_EQ(sample.items(1).name(), "b");
  EXPECT_DOUBLE_EQ(sample.items(1).value(), -2.5);
  EXPECT_EQ(sample.count(), 7u);
}

TEST(TextProto, UnknownFieldNamesFileLineAndField) {
  Sample sample;
  sample.set_count(3);
  const Status status = ParseTextProto("rate_hz: 1\n\n  rate_hzz: 2\n", "odom.textproto", sample);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("odom.textproto:3:"), std::string::npos) << status.error().message;
  EXPECT_NE(status.error().message.find("rate_hzz"), std::string::npos) << status.error().message;
  EXPECT_EQ(sample.count(), 3u);  // untouched on error
  EXPECT_FALSE(sample.has_rate_hz());
}

TEST(TextProto, BadValuesAreErrors) {
  Sample sample;
  EXPECT_FALSE(ParseTextProto("count: -1", "x", sample).ok());           // unsigned
  EXPECT_FALSE(ParseTextProto("mode: MODE_SLOW", "x", sample).ok());      // no such enum value
  EXPECT_FALSE(ParseTextProto("rate_hz: fast", "x", sample).ok());        // not a number
  EXPECT_FALSE(ParseTextProto("items { name: 3 }", "x", sample).ok());    // wrong type
  EXPECT_FALSE(ParseTextProto("items { name: \"a\"", "x", sample).ok());  // unterminated
  const Status status = ParseTextProto("count: 1\ncount: 2", "x", sample);
  EXPECT_FALSE(status.ok());  // a non-repeated field given twice
}

TEST(TextProto, LoadsFilesAndNamesMissingOnes) {
  const auto path = std::filesystem::temp_directory_path() / "flat2d_text_proto_test.textproto";
  {
    std::ofstream file(path);
    file << "rate_hz: 5\n";
  }
  Sample sample;
  ASSERT_TRUE(LoadTextProto(path, sample).ok());
  EXPECT_DOUBLE_EQ(sample.rate_hz(), 5.0);
  std::filesystem::remove(path);
  const Status missing = LoadTextProto(path, sample);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find(path.string()), std::string::npos);
}

}  // namespace
}  // namespace flat2d::hal::config
