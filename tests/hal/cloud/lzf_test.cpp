// LZF decoding against bytes liblzf's lzf_compress wrote (so the decoder is checked
// against the reference encoder, not against itself), and malformed streams that must
// end the decode without reading or writing out of bounds.
#include "hal/cloud/lzf.hpp"

#include <cstring>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "tests/hal/cloud/lzf_golden.hpp"

namespace flat2d::hal::cloud {
namespace {

std::vector<std::uint8_t> Bytes(std::string_view text) { return {text.begin(), text.end()}; }

TEST(Lzf, DecodesWhatLiblzfWrote) {
  const std::vector<std::uint8_t> in = Bytes(kGoldenLzf);
  std::vector<std::uint8_t> out(kGoldenUncompressedBytes);
  ASSERT_EQ(LzfDecompress(in, out), std::optional<std::size_t>(kGoldenUncompressedBytes));
  const GoldenColumns expected;
  EXPECT_EQ(std::memcmp(out.data(), &expected, sizeof expected), 0);
}

TEST(Lzf, LongBackReferenceRepeatsARun) {
  // Literal 'a', then a reference of length 7 + 255 + 2 one byte back: 264 more 'a'.
  const std::vector<std::uint8_t> in = {0x00, 'a', 0xe0, 0xff, 0x00};
  std::vector<std::uint8_t> out(265);
  ASSERT_EQ(LzfDecompress(in, out), std::optional<std::size_t>(265));
  for (const std::uint8_t byte : out) ASSERT_EQ(byte, 'a');
  EXPECT_LE(out.size() - 1, (in.size() - 2) * kLzfMaxExpansion);
}

TEST(Lzf, MalformedStreamsAreRefused) {
  std::vector<std::uint8_t> out(16);
  EXPECT_FALSE(LzfDecompress(std::vector<std::uint8_t>{0x03, 'a', 'b'}, out));         // literal run cut short
  EXPECT_FALSE(LzfDecompress(std::vector<std::uint8_t>{0x00, 'a', 0x20, 0x01}, out));  // reference before the start
  EXPECT_FALSE(LzfDecompress(std::vector<std::uint8_t>{0x00, 'a', 0x20}, out));        // no offset byte
  EXPECT_FALSE(LzfDecompress(std::vector<std::uint8_t>{0x00, 'a', 0xe0}, out));        // no length byte
  EXPECT_FALSE(LzfDecompress(std::vector<std::uint8_t>{0x00, 'a', 0xe0, 0x10, 0x00}, out));  // 25 bytes into 16
  std::vector<std::uint8_t> none;
  EXPECT_FALSE(LzfDecompress(std::vector<std::uint8_t>{0x00, 'a'}, none));
  EXPECT_EQ(LzfDecompress({}, none), std::optional<std::size_t>(0));
}

}  // namespace
}  // namespace flat2d::hal::cloud
