// The real candump logs of ../shared/data/can (PROVENANCE.md, section can/): frame counts,
// ids, durations, zero malformed lines, and byte-exact reader -> writer round trips.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "hal/can/candump_log.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::can {
namespace {

struct LogSummary {
  std::uint64_t frames = 0;
  std::set<std::pair<bool, std::uint32_t>> ids;  // (extended, id)
  std::map<std::uint32_t, std::uint64_t> frames_per_id;
  TimeNs first_ns = 0;
  TimeNs last_ns = 0;
  std::uint64_t backward_steps = 0;
  CandumpReaderStats stats;
};

LogSummary Summarize(const std::filesystem::path& path) {
  LogSummary summary;
  Result<CandumpReader> reader = CandumpReader::Open(path);
  EXPECT_TRUE(reader.ok()) << reader.error().message;
  if (!reader.ok()) return summary;
  CanFrame frame;
  while (reader->Next(frame)) {
    if (summary.frames == 0) summary.first_ns = frame.time_ns;
    if (frame.time_ns < summary.last_ns) ++summary.backward_steps;
    summary.last_ns = frame.time_ns;
    ++summary.frames;
    summary.ids.insert({frame.extended, frame.id});
    ++summary.frames_per_id[frame.id];
  }
  summary.stats = reader->stats();
  return summary;
}

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Reads `path`, writes every frame to a temp file and returns that file's bytes.
std::string Rewrite(const std::filesystem::path& path, const CandumpWriterOptions& options) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() /
                                    ("candump_rewrite_" + std::to_string(::getpid()) + ".log");
  Result<CandumpReader> reader = CandumpReader::Open(path);
  Result<CandumpWriter> writer = CandumpWriter::Open(out, options);
  EXPECT_TRUE(reader.ok() && writer.ok());
  if (!reader.ok() || !writer.ok()) return {};
  CanFrame frame;
  while (reader->Next(frame)) {
    const Status written = writer->Write(frame, reader->last_direction());
    EXPECT_TRUE(written.ok()) << written.error().message;
    if (!written.ok()) break;
  }
  EXPECT_TRUE(writer->Close().ok());
  std::string bytes = ReadBytes(out);
  std::filesystem::remove(out);
  return bytes;
}

void ExpectClean(const LogSummary& summary) {
  EXPECT_EQ(summary.stats.malformed, 0u);
  EXPECT_EQ(summary.stats.lines, summary.frames);
  EXPECT_EQ(summary.stats.error_frames + summary.stats.remote_frames + summary.stats.fd_frames, 0u);
  EXPECT_EQ(summary.backward_steps, 0u);
  EXPECT_TRUE(summary.stats.read_error.empty());
}

TEST(CandumpRealData, CivicTypeR) {
  FLAT2D_REQUIRE_DATA(path, "can/eldominio_candump/civic_19_type_r__turnonanddrive.log");
  const LogSummary summary = Summarize(path);
  ExpectClean(summary);
  EXPECT_EQ(summary.frames, 28835u);
  EXPECT_EQ(summary.ids.size(), 57u);
  EXPECT_EQ(summary.frames_per_id.at(0x1D0), 803u);  // WHEEL_SPEEDS
  EXPECT_EQ(summary.first_ns, 1'674'148'739'212'264'000);
  EXPECT_EQ(summary.last_ns - summary.first_ns, 65'481'943'000);  // 65.5 s
  EXPECT_EQ(summary.stats.FramesOn("can0"), 28835u);
}

TEST(CandumpRealData, CivicTypeRRoundTripIsByteExact) {
  FLAT2D_REQUIRE_DATA(path, "can/eldominio_candump/civic_19_type_r__turnonanddrive.log");
  const std::string original = ReadBytes(path);
  const std::string rewritten = Rewrite(path, {});
  ASSERT_EQ(rewritten.size(), original.size());
  EXPECT_TRUE(rewritten == original);
}

TEST(CandumpRealData, ScionXbTrymph) {
  FLAT2D_REQUIRE_DATA(path, "can/eldominio_candump/xb__trymph.log");
  const LogSummary summary = Summarize(path);
  ExpectClean(summary);
  EXPECT_EQ(summary.frames, 2979u);
  EXPECT_EQ(summary.ids.size(), 39u);
  EXPECT_EQ(summary.frames_per_id.at(0x24), 110u);  // KINEMATICS, heavily decimated
  EXPECT_EQ(summary.last_ns - summary.first_ns, 20'415'739'000);  // 20.4 s
  EXPECT_TRUE(Rewrite(path, {}) == ReadBytes(path));
}

TEST(CandumpRealData, ToyotaRav4HybridBus0) {
  FLAT2D_REQUIRE_DATA(path,
                      "can/toyota_rav4h_comma2k19/DERIVED_comma2k19_rav4h_seg40_bus0.candump.log");
  const LogSummary summary = Summarize(path);
  ExpectClean(summary);
  EXPECT_EQ(summary.frames, 53800u);
  EXPECT_EQ(summary.frames_per_id.at(0xAA), 4974u);  // WHEEL_SPEEDS
  EXPECT_EQ(summary.frames_per_id.at(0x24), 4974u);  // KINEMATICS
  EXPECT_EQ(summary.frames_per_id.at(0x25), 4974u);  // STEER_ANGLE_SENSOR
  EXPECT_EQ(summary.frames_per_id.at(0xB4), 2487u);  // SPEED
  // comma's monotonic seconds since boot, kept as given.
  EXPECT_EQ(summary.first_ns, 46'408'584'930'000);
  EXPECT_EQ(summary.last_ns - summary.first_ns, 59'992'700'000);  // 60.0 s
  // The converter wrote unpadded seconds; with that one option the bytes come back.
  EXPECT_TRUE(Rewrite(path, {.seconds_digits = 0}) == ReadBytes(path));
}

TEST(CandumpRealData, ToyotaRav4HybridAllBuses) {
  FLAT2D_REQUIRE_DATA(
      path, "can/toyota_rav4h_comma2k19/DERIVED_comma2k19_rav4h_seg40_allbuses.candump.log");
  const LogSummary summary = Summarize(path);
  ExpectClean(summary);
  EXPECT_EQ(summary.frames, 135468u);
  EXPECT_EQ(summary.stats.FramesOn("can0"), 53800u);
  EXPECT_EQ(summary.stats.FramesOn("can1"), 45000u);
  EXPECT_EQ(summary.stats.FramesOn("can128"), 12434u);
  EXPECT_EQ(summary.stats.FramesOn("can129"), 24234u);
}

TEST(CandumpRealData, VerifiedCanToyota) {
  FLAT2D_REQUIRE_DATA(
      path, "can/toyota_verifiedcan/DERIVED_verifiedcan_toyota_2020-02-03-14-31-11.candump.log");
  const LogSummary summary = Summarize(path);
  ExpectClean(summary);
  EXPECT_EQ(summary.frames, 68178u);
  EXPECT_EQ(summary.stats.FramesOn("can0") + summary.stats.FramesOn("can1"), 68178u);
  EXPECT_EQ(summary.stats.FramesOn("can0"), 39331u);
  EXPECT_EQ(summary.stats.FramesOn("can1"), 28847u);
  EXPECT_EQ(summary.frames_per_id.at(0xAA), 3573u);  // the logger dropped frames
  EXPECT_EQ(summary.frames_per_id.at(0x24), 1527u);
  EXPECT_EQ(summary.frames_per_id.at(0xB4), 1202u);
  EXPECT_EQ(summary.frames_per_id.at(0x25), 2703u);
  EXPECT_EQ(summary.last_ns - summary.first_ns, 115'279'252'000);  // 115.3 s
  EXPECT_TRUE(Rewrite(path, {}) == ReadBytes(path));
}

}  // namespace
}  // namespace flat2d::hal::can
