// CandumpReader over memory and files (malformed lines, long lines, counters) and
// CandumpWriter round trips.
#include "hal/can/candump_log.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::can {
namespace {

// A file under the temp folder, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& stem)
      : path_(std::filesystem::temp_directory_path() /
              (stem + "_" + std::to_string(::getpid()) + ".log")) {}
  ~TempFile() { std::filesystem::remove(path_); }
  const std::filesystem::path& path() const { return path_; }

  void Write(const std::string& text) const {
    std::ofstream out(path_, std::ios::binary);
    out << text;
  }
  std::string Read() const {
    std::ifstream in(path_, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

 private:
  std::filesystem::path path_;
};

std::vector<CanFrame> Drain(CanFrameSource& source) {
  std::vector<CanFrame> frames;
  CanFrame frame;
  while (source.Next(frame)) frames.push_back(frame);
  return frames;
}

TEST(CandumpReader, MalformedLinesAreCountedWithTheirNumbersAndSkipped) {
  const std::string log =
      "(1.000000) can0 100#01\n"        // 1
      "\n"                              // 2 blank
      "(1.000100) can0 101#0G\n"        // 3 bad hex
      "# a comment\n"                   // 4
      "(1.000200) can0 102#012\n"       // 5 odd digits
      "(1.000300) can0 103#01\n"        // 6
      "(1.000400) can0 800#01\n"        // 7 id too large for 3 digits
      "(1.000500) can0 104##0" + std::string(18, '0') + "\n"  // 8 FD length 9
      "(1.000600) can0\n"               // 9 missing frame
      "DROPCOUNT: dropped 1 CAN frame on 'can0' socket (total drops 1)\n"  // 10
      "(1.000700) can1 105#R2 T\n"      // 11
      "(1.000800) can0 106#112233445566778899\n"  // 12 classic too long
      "garbage\n"                       // 13
      "(1.000900) can1 107#0102";       // 14, no final newline
  CandumpReader reader = CandumpReader::FromString(log);
  const std::vector<CanFrame> frames = Drain(reader);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].id, 0x100u);
  EXPECT_EQ(frames[1].id, 0x103u);
  EXPECT_EQ(frames[2].id, 0x105u);
  EXPECT_TRUE(frames[2].remote);
  EXPECT_EQ(frames[3].id, 0x107u);
  EXPECT_EQ(frames[3].time_ns, 1'000'900'000);
  const CandumpReaderStats& stats = reader.stats();
  EXPECT_EQ(stats.lines, 14u);
  EXPECT_EQ(stats.frames, 4u);
  EXPECT_EQ(stats.ignored_lines, 2u);
  EXPECT_EQ(stats.drop_notices, 1u);
  EXPECT_EQ(stats.remote_frames, 1u);
  EXPECT_EQ(stats.transmitted, 1u);
  EXPECT_EQ(stats.malformed, 7u);
  const std::vector<CandumpMalformedLine> expected = {
      {3, CandumpError::kBadDataHex},          {5, CandumpError::kOddDataDigits},
      {7, CandumpError::kStandardIdTooLarge},  {8, CandumpError::kInvalidFdLength},
      {9, CandumpError::kNoFrame},             {12, CandumpError::kClassicDataTooLong},
      {13, CandumpError::kNoTimestamp}};
  ASSERT_EQ(stats.first_malformed.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(stats.first_malformed[i].line, expected[i].line) << i;
    EXPECT_EQ(stats.first_malformed[i].error, expected[i].error) << i;
  }
  EXPECT_EQ(stats.FramesOn("can0"), 2u);
  EXPECT_EQ(stats.FramesOn("can1"), 2u);
  EXPECT_EQ(stats.FramesOn("can2"), 0u);
}

TEST(CandumpReader, KeepsTheFirstSixteenMalformedLinesAndCountsAll) {
  std::string log;
  for (int i = 0; i < 40; ++i) log += (i % 2 == 0) ? "bad line\n" : "(2.000000) can0 123#00\n";
  CandumpReader reader = CandumpReader::FromString(log);
  EXPECT_EQ(Drain(reader).size(), 20u);
  EXPECT_EQ(reader.stats().malformed, 20u);
  ASSERT_EQ(reader.stats().first_malformed.size(), kMaxRecordedMalformedLines);
  EXPECT_EQ(reader.stats().first_malformed.front().line, 1u);
  EXPECT_EQ(reader.stats().first_malformed.back().line, 31u);
}

TEST(CandumpReader, CountsFramesPerInterfaceUpToEightNames) {
  std::string log;
  for (int i = 0; i < 10; ++i) log += "(1.000000) can" + std::to_string(i) + " 123#00\n";
  log += "(1.000000) can9 123#00\n";
  CandumpReader reader = CandumpReader::FromString(log);
  EXPECT_EQ(Drain(reader).size(), 11u);
  EXPECT_EQ(reader.stats().interfaces.size(), kMaxCountedInterfaces);
  EXPECT_EQ(reader.stats().FramesOn("can7"), 1u);
  EXPECT_EQ(reader.stats().other_interface_frames, 3u);
}

TEST(CandumpReader, OverlongLinesAreMalformedInMemoryAndInFiles) {
  // 2000 bytes: over the line limit; 100000 bytes: over the 64 KiB read window too.
  const std::string log = "(1.000000) can0 100#01\n" + std::string(2000, 'x') + "\n" +
                          "(1.000000) can0 101#01\n" + std::string(100000, '(') + "\n" +
                          "(1.000000) can0 102#01\n" + std::string(3000, 'y');
  TempFile file("candump_long_lines");
  file.Write(log);
  Result<CandumpReader> from_file = CandumpReader::Open(file.path());
  ASSERT_TRUE(from_file.ok()) << from_file.error().message;
  CandumpReader from_memory = CandumpReader::FromString(log);
  for (CandumpReader* reader : {&*from_file, &from_memory}) {
    const std::vector<CanFrame> frames = Drain(*reader);
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(frames[2].id, 0x102u);
    EXPECT_EQ(reader->stats().lines, 6u);
    ASSERT_EQ(reader->stats().malformed, 3u);
    EXPECT_EQ(reader->stats().first_malformed[0].line, 2u);
    EXPECT_EQ(reader->stats().first_malformed[1].line, 4u);
    EXPECT_EQ(reader->stats().first_malformed[2].line, 6u);
    EXPECT_EQ(reader->stats().first_malformed[1].error, CandumpError::kLineTooLong);
  }
}

TEST(CandumpReader, LinesAcrossReadBlocksAreWhole) {
  // ~150 KB of lines: several 64 KiB windows, lines split across their edges.
  std::string log;
  for (int i = 0; i < 5000; ++i) {
    log += '(';  // appended piecewise: "(" + std::string trips GCC 12's -Wrestrict
    log += std::to_string(1000 + i);
    log += ".123456) can0 1AB#0102030405060708\n";
  }
  TempFile file("candump_blocks");
  file.Write(log);
  Result<CandumpReader> reader = CandumpReader::Open(file.path());
  ASSERT_TRUE(reader.ok());
  const std::vector<CanFrame> frames = Drain(*reader);
  ASSERT_EQ(frames.size(), 5000u);
  EXPECT_EQ(reader->stats().malformed, 0u);
  for (int i = 0; i < 5000; ++i) {
    ASSERT_EQ(frames[static_cast<std::size_t>(i)].time_ns, (1000 + i) * kNsPerSecond + 123'456'000);
  }
}

TEST(CandumpReader, OpenNamesAMissingFile) {
  const Result<CandumpReader> reader = CandumpReader::Open("/nonexistent/drive.log");
  ASSERT_FALSE(reader.ok());
  EXPECT_EQ(reader.error().message,
            "cannot open candump log /nonexistent/drive.log: No such file or directory");
}

TEST(CandumpReader, NextAllocatesNothing) {
  std::string log;
  for (int i = 0; i < 1000; ++i) {
    log += "(1.000000) can0 123#0102 R\n(1.000000) can1 12345678##1" + std::string(24, 'A') +
           "\nbad\n";
  }
  CandumpReader reader = CandumpReader::FromString(log);
  CanFrame frame;
  // From the first line on: counters were reserved at construction, and interface
  // names fit in std::string's inline buffer.
  const std::uint64_t before = testing::AllocationCount();
  std::size_t frames = 0;
  while (reader.Next(frame)) ++frames;
  EXPECT_EQ(testing::AllocationCount(), before);
  EXPECT_EQ(frames, 2000u);
  EXPECT_EQ(reader.stats().malformed, 1000u);
}

TEST(CandumpWriter, RoundTripIsByteExact) {
  const std::string log =
      "(1674148739.212264) can0 112#FF0015\n"
      "(1674148739.212487) can1 14A#FFF1000007FFF124 T\n"
      "(1674148739.212712) can0 1ABCDEF0#R3\n"
      "(1674148739.212712) can0 123##5001122334455667788990011\n"
      "(1674148739.213000) can0 20000004#0004000000000000\n"
      "(1674148739.213001) can0 7FF# R\n";
  CandumpReader reader = CandumpReader::FromString(log);
  TempFile file("candump_round_trip");
  Result<CandumpWriter> writer = CandumpWriter::Open(file.path());
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  CanFrame frame;
  while (reader.Next(frame)) ASSERT_TRUE(writer->Write(frame, reader.last_direction()).ok());
  ASSERT_TRUE(writer->Close().ok());
  EXPECT_EQ(writer->frames_written(), 6u);
  EXPECT_EQ(file.Read(), log);
}

TEST(CandumpWriter, RefusesUnwritableFramesAndKeepsTheFileClean) {
  TempFile file("candump_refusals");
  Result<CandumpWriter> writer = CandumpWriter::Open(file.path());
  ASSERT_TRUE(writer.ok());
  CanFrame frame;
  frame.id = 0x900;
  const Status refused = writer->Write(frame);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("standard id above 0x7FF"), std::string::npos)
      << refused.error().message;
  frame.id = 0x100;
  ASSERT_TRUE(writer->Write(frame).ok());
  ASSERT_TRUE(writer->Close().ok());
  EXPECT_FALSE(writer->Write(frame).ok());  // closed
  EXPECT_EQ(file.Read(), "(0000000000.000000) can0 100#\n");
  EXPECT_FALSE(CandumpWriter::Open("/nonexistent/out.log").ok());
}

}  // namespace
}  // namespace flat2d::hal::can
