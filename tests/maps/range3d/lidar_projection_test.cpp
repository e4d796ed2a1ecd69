// LidarProjection's firing-aligned columns, through the real packet codec: every firing
// sequence a sensor sends must land in one column of the image, whatever the column
// borders; without the alignment many straddle two (what Algorithm 7 stumbled on).
#include "maps/range3d/range_frame.hpp"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "hal/velodyne/packet_decoder.hpp"
#include "hal/velodyne/packet_encoder.hpp"

namespace flat2d::maps::range3d {
namespace {

using hal::velodyne::Model;

constexpr int kColumns = 2160;
constexpr double kPi = 3.14159265358979;

struct Turn {
  Model model;
  std::uint8_t product_id;
  int block_gap_units;  // azimuth step between blocks, hundredths of a degree
  double block_period_us;
};

// The rotation speed that a block step of `gap` hundredths of a degree per block period is.
double RpmOf(const Turn& turn) {
  const double degrees_per_us = turn.block_gap_units * 0.01 / turn.block_period_us;
  return degrees_per_us * 1e6 / 360.0 * 60.0;
}

// A decoded firing sequence: the columns its points land in, and whether it starts within
// the decoder's azimuth quantum of a column border. The decoder rounds each laser's
// interpolated azimuth to the packet's unit, 0.01 deg (0.06 of a column), so such a sequence
// may straddle the border whatever the alignment.
struct SequenceColumns {
  std::set<int> columns;
  bool near_border = false;
};

// One turn of packets, every laser returning at 10 m, starting 5 hundredths of a degree
// past 0.
std::vector<SequenceColumns> FanColumns(const Turn& turn, const RangeProjection& projection) {
  const hal::velodyne::LaserTable table = hal::velodyne::DefaultLaserTable(turn.model);
  hal::velodyne::PacketDecoder decoder(table);
  hal::velodyne::DecodedPacket decoded;
  std::vector<SequenceColumns> fans;
  constexpr int kBlocks = static_cast<int>(hal::velodyne::kBlocksPerPacket);
  constexpr int kChannels = static_cast<int>(hal::velodyne::kChannelsPerBlock);
  int azimuth_units = 5;
  while (azimuth_units < 36000 - kBlocks * turn.block_gap_units) {
    hal::velodyne::DataPacketContent content;
    content.product_id = turn.product_id;
    for (int block = 0; block < kBlocks; ++block, azimuth_units += turn.block_gap_units) {
      content.block_azimuth_units[static_cast<std::size_t>(block)] = static_cast<std::uint16_t>(azimuth_units);
      for (int channel = 0; channel < kChannels; ++channel) {
        const int laser = channel % table.num_lasers;
        content.records[static_cast<std::size_t>(block)][static_cast<std::size_t>(channel)].distance_units =
            hal::velodyne::RawDistance(10.0, table, laser);
      }
    }
    const auto bytes = hal::velodyne::EncodeDataPacket(content);
    EXPECT_TRUE(bytes.ok());
    decoder.Decode(*bytes, decoded);
    EXPECT_EQ(decoded.error, hal::velodyne::PacketError::kNone);
    for (int f = 0; f < decoded.num_fans; ++f) {
      SequenceColumns sequence;
      const hal::velodyne::Fan& fan = decoded.fans[static_cast<std::size_t>(f)];
      for (int laser = 0; laser < fan.num_lasers; ++laser) {
        const Pixel pixel = projection.Project(fan.returns[static_cast<std::size_t>(laser)].xyz);
        EXPECT_TRUE(pixel.valid());
        sequence.columns.insert(pixel.col);
      }
      // The image's azimuth is the decoder's negated (decoder x = h cos a, y = -h sin a).
      const double column = (kPi - static_cast<double>(fan.azimuth_rad)) / (2.0 * kPi) * kColumns;
      const double from_border = std::abs(column - std::round(column));
      sequence.near_border = from_border < 0.07;
      fans.push_back(sequence);
    }
  }
  return fans;
}

std::size_t Straddling(const std::vector<SequenceColumns>& fans, bool count_near_border) {
  std::size_t count = 0;
  for (const SequenceColumns& fan : fans) {
    if (fan.near_border && !count_near_border) continue;
    count += fan.columns.size() > 1 ? 1 : 0;
  }
  return count;
}

std::size_t NearBorder(const std::vector<SequenceColumns>& fans) {
  std::size_t count = 0;
  for (const SequenceColumns& fan : fans) count += fan.near_border ? 1 : 0;
  return count;
}

class FiringColumns : public ::testing::TestWithParam<Turn> {};

TEST_P(FiringColumns, EverySequenceSharesAColumn) {
  const Turn turn = GetParam();
  const auto aligned = FanColumns(turn, LidarProjection(SensorModelOf(turn.model), kColumns, RpmOf(turn)));
  const auto by_azimuth = FanColumns(turn, LidarProjection(SensorModelOf(turn.model), kColumns));
  ASSERT_GT(aligned.size(), 1500U);
  EXPECT_EQ(Straddling(aligned, false), 0U) << "of " << aligned.size() << " sequences at " << RpmOf(turn) << " rpm";
  EXPECT_LT(NearBorder(aligned), aligned.size() / 5);
  // By azimuth alone a sequence spans 0.37 (HDL-32E) or 0.75 (VLP-16) of a column: a border
  // cuts that share of them.
  EXPECT_GT(Straddling(by_azimuth, true), aligned.size() / 4) << "of " << by_azimuth.size();
}

// 600 rpm is 40 hundredths of a degree per VLP-16 block (110.592 us), 17 per HDL-32E block
// (46.08 us); the decoder interpolates each laser's azimuth within the block from the step.
INSTANTIATE_TEST_SUITE_P(Velodyne, FiringColumns,
                         ::testing::Values(Turn{Model::kVlp16, hal::velodyne::kProductIdVlp16, 40, 110.592},
                                           Turn{Model::kHdl32e, hal::velodyne::kProductIdHdl32e, 17, 46.08}),
                         [](const auto& turn) { return std::string(turn.param.model == Model::kVlp16 ? "Vlp16" : "Hdl32e"); });

// The VLP-32C's lasers point up to 4 deg apart in azimuth: a sequence spans 25 columns, and
// only azimuth keeps a pole's points together, so its columns are not shifted.
TEST(FiringColumns, Vlp32cKeepsAzimuthColumns) {
  const RangeProjection aligned = LidarProjection(SensorModel::kVlp32c, kColumns, 600.0);
  const RangeProjection by_azimuth = LidarProjection(SensorModel::kVlp32c, kColumns);
  for (int k = 0; k < 720; ++k) {
    const float a = 0.5F * static_cast<float>(k) * 3.14159265F / 180.0F;
    for (const float z : {-2.0F, 0.0F, 1.0F}) {
      const Eigen::Vector3f p(10.0F * std::cos(a), 10.0F * std::sin(a), z);
      EXPECT_EQ(aligned.Project(p).col, by_azimuth.Project(p).col);
    }
  }
}

}  // namespace
}  // namespace flat2d::maps::range3d
