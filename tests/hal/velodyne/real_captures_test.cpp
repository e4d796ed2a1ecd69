// Every real capture in shared/data/velodyne, decoded end to end. Expected counts come
// from shared/data/PROVENANCE.md (measured there with an independent reader): packet
// counts, product, return mode, azimuth wraps (complete revolutions = wraps - 1).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/capture_summary.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::velodyne {
namespace {

struct Capture {
  const char* path;
  Model model;
  ReturnMode mode;
  std::uint64_t data_packets;
  std::uint64_t position_packets;
  std::uint64_t complete_revolutions;
  // 1.2 x the model's specified range (100 m VLP-16 and HDL-32E, 200 m VLP-32C): real
  // units report retro-reflectors somewhat beyond the specification (110 m seen here).
  double max_range_m;
  int min_points_per_turn;   // a full turn of this sensor indoors or outdoors has at least
  int max_points_per_turn;   // channel records of one turn at the capture's rotation rate
};

void PrintTo(const Capture& capture, std::ostream* os) { *os << capture.path; }

class RealCapture : public ::testing::TestWithParam<Capture> {};

CaptureSummary Summarize(const std::filesystem::path& path) {
  auto source = net::OpenCapture(path);
  EXPECT_TRUE(source.ok()) << (source.ok() ? "" : source.error().message);
  if (!source.ok()) return {};
  return SummarizeCapture(**source, {});
}

TEST_P(RealCapture, DecodesToTheRecordedFacts) {
  const Capture& expected = GetParam();
  FLAT2D_REQUIRE_DATA(path, std::string("velodyne/") + expected.path);
  const CaptureSummary summary = Summarize(path);

  ASSERT_TRUE(summary.identification.has_value())
      << (summary.model_error ? summary.model_error->message : "no identification");
  EXPECT_EQ(summary.identification->model, expected.model);
  EXPECT_EQ(summary.product, ModelName(expected.model));
  EXPECT_EQ(summary.identification->return_mode, expected.mode);
  EXPECT_EQ(summary.stream.data_packets, expected.data_packets);
  EXPECT_EQ(summary.stream.position_packets, expected.position_packets);
  EXPECT_EQ(summary.stream.malformed, 0u);
  EXPECT_EQ(summary.stream.out_of_order, 0u);
  EXPECT_EQ(summary.stream.dropped_fans, 0u);
  EXPECT_EQ(summary.stream.revolutions, expected.complete_revolutions);

  std::uint64_t points = 0;
  for (const RevolutionSummary& revolution : summary.revolutions) {
    points += static_cast<std::uint64_t>(revolution.points);
    EXPECT_TRUE(revolution.stamps_monotonic) << "revolution " << revolution.sequence;
    EXPECT_LE(revolution.max_range_m, expected.max_range_m) << "revolution " << revolution.sequence;
    if (!revolution.complete) continue;
    EXPECT_GE(revolution.points, expected.min_points_per_turn) << "revolution " << revolution.sequence;
    EXPECT_LE(revolution.points, expected.max_points_per_turn) << "revolution " << revolution.sequence;
    EXPECT_GT(revolution.end_ns, revolution.start_ns);
  }
  EXPECT_EQ(points, summary.stream.points);
  EXPECT_GT(points, 0u);
}

// Elevation of every far return, from its decoded xyz, equals its laser's table value.
TEST_P(RealCapture, ReturnsLieOnTheirLaserElevation) {
  const Capture& expected = GetParam();
  FLAT2D_REQUIRE_DATA(path, std::string("velodyne/") + expected.path);
  auto source = net::OpenCapture(path);
  ASSERT_TRUE(source.ok());
  const LaserTable table = DefaultLaserTable(expected.model);
  std::array<int, kMaxLasers> checked{};
  double worst_deg = 0.0;
  VelodyneStream stream({}, [&](const Revolution& revolution) {
    for (const Fan& fan : revolution.fans) {
      for (int laser = 0; laser < fan.num_lasers; ++laser) {
        const LaserReturn& r = fan.returns[static_cast<std::size_t>(laser)];
        if (r.range_m < 2.0f) continue;
        // Seen from the laser's own origin, which the VLP-16 table shifts by its vertical
        // correction perpendicular to the beam (manual Table 9-1).
        const double offset = table.lasers[static_cast<std::size_t>(laser)].vertical_offset_m;
        const double table_elevation = ManualElevationDeg(expected.model, laser);
        const double horizontal = r.xyz.head<2>().cast<double>().norm() +
                                  offset * std::sin(table_elevation / kRadToDeg);
        const double vertical = static_cast<double>(r.xyz.z()) - offset * std::cos(table_elevation / kRadToDeg);
        const double elevation = std::atan2(vertical, horizontal) * kRadToDeg;
        const double error = std::abs(elevation - table_elevation);
        worst_deg = std::max(worst_deg, error);
        ++checked[static_cast<std::size_t>(laser)];
      }
    }
  });
  while (auto datagram = (*source)->Next()) stream.Push(*datagram);
  stream.Finish();
  // Float xyz and 2 mm range steps keep the error far below the table's 0.01 deg rounding.
  EXPECT_LT(worst_deg, 0.01) << "worst elevation error (deg)";
  int lasers_checked = 0;
  for (int count : checked) lasers_checked += count > 0 ? 1 : 0;
  EXPECT_GE(lasers_checked, LaserCount(expected.model) / 2) << "too few lasers saw far returns";
}

// Complete-revolution point bounds: a turn has 12 blocks x 32 records per packet times
// packets per turn (754 / 1808 / 1507 packets/s over the rotation rate).
INSTANTIATE_TEST_SUITE_P(
    Velodyne, RealCapture,
    ::testing::Values(
        Capture{"vlp16/mrpt_sample_velodyne_vlp16_gps.pcap", Model::kVlp16,
                ReturnMode::kStrongest, 293, 57, 3, 120.0, 10000, 29000},
        Capture{"vlp16/rust-lidar-utils_velodyne_vlp16_prod0x21.pcap", Model::kVlp16,
                ReturnMode::kStrongest, 84, 16, 0, 120.0, 0, 0},
        Capture{"vlp16/rust-lidar-utils_velodyne_example.pcap", Model::kVlp16,
                ReturnMode::kStrongest, 84, 0, 0, 120.0, 0, 0},
        Capture{"vlp16/DERIVED_nebula_vlp16_dual_1673400471837873222.pcap", Model::kVlp16,
                ReturnMode::kDual, 603, 0, 3, 120.0, 10000, 58000},
        Capture{"hdl32e/mrpt_sample_velodyne_hdl32.pcap", Model::kHdl32e,
                ReturnMode::kStrongest, 500, 0, 2, 120.0, 30000, 77000},
        Capture{"hdl32e/rust-lidar-utils_hdl32_example.pcap", Model::kHdl32e,
                ReturnMode::kStrongest, 876, 100, 5, 120.0, 30000, 70000},
        Capture{"hdl32e/rust-lidar-utils_velodyne_vlp32_is_hdl32e.pcap", Model::kHdl32e,
                ReturnMode::kStrongest, 91, 9, 0, 120.0, 0, 0},
        Capture{"vlp32c/DERIVED_nebula_vlp32c_1713492677464078412.pcap", Model::kVlp32c,
                ReturnMode::kStrongest, 379, 0, 4, 240.0, 10000, 58000},
        Capture{"raw_payloads/einride_vlp16-go_testdata_recording.bin", Model::kVlp16,
                ReturnMode::kStrongest, 1000, 0, 12, 120.0, 10000, 29000},
        Capture{"raw_payloads/floriantimm_vlp16_dual_300rpm_C++_0.bin", Model::kVlp16,
                ReturnMode::kDual, 1500, 0, 5, 120.0, 20000, 116000},
        Capture{"raw_payloads/floriantimm_vlp16_last_300rpm_C++_Debug_0.bin", Model::kVlp16,
                ReturnMode::kLast, 1500, 0, 9, 120.0, 20000, 58000}),
    [](const ::testing::TestParamInfo<Capture>& param) {
      std::string name = param.param.path;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

TEST(RealCaptureFacts, Vlp16WithHdl32eProductIdIsReported) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/vlp16/rust-lidar-utils_velodyne_vlp16_prod0x21.pcap");
  const CaptureSummary summary = Summarize(path);
  ASSERT_TRUE(summary.identification.has_value());
  EXPECT_EQ(summary.identification->decided_by, "packet timing");
  EXPECT_EQ(summary.identification->product_id, 0x21);
  ASSERT_FALSE(summary.identification->disagreements.empty());
  EXPECT_NE(summary.identification->disagreements[0].find("HDL-32E"), std::string::npos);
}

TEST(RealCaptureFacts, GpsPositionPacketsGiveAbsoluteTime) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/vlp16/mrpt_sample_velodyne_vlp16_gps.pcap");
  const CaptureSummary summary = Summarize(path);
  EXPECT_EQ(summary.time_source, TimeSource::kGps);
  ASSERT_FALSE(summary.revolutions.empty());
  // The first packet's device time is 1,082,340,595 us past the hour; the $GPRMC
  // sentences say 2016-01-21 08:18:02 UTC, so it fired at 08:18:02.340595 UTC
  // (1453363200 s is 2016-01-21T08:00:00Z). The capture host's clock ran 0.368 s ahead.
  EXPECT_EQ(summary.revolutions.front().start_ns, 1'453'364'282'340'595'000LL);
}

TEST(RealCaptureFacts, FovLimitedVlp32cPausesWithoutLoss) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/vlp32c/DERIVED_nebula_vlp32c_1713492677464078412.pcap");
  const CaptureSummary summary = Summarize(path);
  EXPECT_EQ(summary.stream.lost_packets, 0u);
  EXPECT_GE(summary.stream.pauses, 4u);  // one 50 ms pause per turn outside the FOV
  for (const RevolutionSummary& revolution : summary.revolutions) {
    if (revolution.complete) {
      EXPECT_NEAR(revolution.swept_azimuth_deg, 180.0, 10.0);
    }
  }
}

TEST(RealCaptureFacts, DroppedPacketsInDualCaptureAreCounted) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/raw_payloads/floriantimm_vlp16_dual_300rpm_C++_0.bin");
  const CaptureSummary summary = Summarize(path);
  // Device time steps by 663-664 us except at 32 gaps of 1.3 to 15.9 ms (PROVENANCE.md
  // names the seven longest); each gap of s us lost round(s / 663.55) - 1 packets.
  EXPECT_EQ(summary.stream.lost_packets, 455u);
  EXPECT_EQ(summary.stream.pauses, 0u);
}

TEST(RealCaptureFacts, Vls128IsNamedNotDecoded) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/vls128/DERIVED_nebula_vls128_1614315746471294674.pcap");
  const CaptureSummary summary = Summarize(path);
  EXPECT_FALSE(summary.identification.has_value());
  ASSERT_TRUE(summary.model_error.has_value());
  EXPECT_EQ(summary.product, "VLS-128");
  EXPECT_NE(summary.model_error->message.find("VLS-128"), std::string::npos);
  EXPECT_EQ(summary.stream.data_packets, 2193u);
  EXPECT_EQ(summary.stream.undecodable_model, 2193u);
  EXPECT_EQ(summary.stream.points, 0u);
}

}  // namespace
}  // namespace flat2d::hal::velodyne
