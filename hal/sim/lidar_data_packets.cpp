#include "hal/sim/lidar_data_packets.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

#include "hal/sim/stateless_random.hpp"

namespace flat2d::hal::sim {
namespace {

using velodyne::kBlocksPerPacket;
using velodyne::kChannelsPerBlock;

constexpr int kUnitsPerTurn = velodyne::kAzimuthUnitsPerTurn;
constexpr double kUnitsToRad = 2.0 * std::numbers::pi / kUnitsPerTurn;
constexpr double kRadToUnits = 1.0 / kUnitsToRad;  // as PacketDecoder
constexpr std::uint64_t kRangeStream = 0x4C49444152ULL;  // "LIDAR": keeps streams apart

int WrapUnits(int units) {
  if (units >= kUnitsPerTurn) return units - kUnitsPerTurn;
  if (units < 0) return units + kUnitsPerTurn;
  return units;
}

std::uint8_t ProductIdOf(velodyne::Model model) {
  switch (model) {
    case velodyne::Model::kVlp16: return velodyne::kProductIdVlp16;
    case velodyne::Model::kHdl32e: return velodyne::kProductIdHdl32e;
    case velodyne::Model::kVlp32c: return velodyne::kProductIdVlp32c;
  }
  return velodyne::kProductIdVlp16;
}

double NsToSeconds(TimeNs ns) { return static_cast<double>(ns) * 1e-9; }

}  // namespace

DataPacketSimulator::DataPacketSimulator(const Scene& scene, const Trajectory& trajectory,
                                         const LidarOptions& options, std::uint64_t seed)
    : scene_(&scene),
      trajectory_(&trajectory),
      options_(options),
      seed_(seed),
      table_(LaserTableOf(options)),
      timing_(velodyne::TimingFor(options.model)),
      schedule_(options.model, options.return_mode),
      packet_period_ns_(std::llround(velodyne::PacketPeriodUs(options.model, options.return_mode) * 1e3)),
      block_period_ns_(std::llround(timing_.block_period_us * 1e3)),
      cos_table_(static_cast<std::size_t>(kUnitsPerTurn)),
      sin_table_(static_cast<std::size_t>(kUnitsPerTurn)),
      world_time_offset_s_(trajectory.world_time_offset_s()) {
  for (int units = 0; units < kUnitsPerTurn; ++units) {
    cos_table_[static_cast<std::size_t>(units)] = std::cos(units * kUnitsToRad);
    sin_table_[static_cast<std::size_t>(units)] = std::sin(units * kUnitsToRad);
  }
  for (std::size_t id = 0; id < lasers_.size(); ++id) {
    const velodyne::LaserCorrection& laser = table_.lasers[id];
    lasers_[id] = {std::cos(laser.elevation_rad), std::sin(laser.elevation_rad),
                   laser.vertical_offset_m, laser.horizontal_offset_m};
  }
  // The same single-precision expressions as PacketDecoder, so the integer azimuths agree.
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const int laser_id = static_cast<int>(c) % timing_.lasers_per_fan;
    const double rot_correction = table_.lasers[static_cast<std::size_t>(laser_id)].rot_correction_rad;
    channels_[c].block_fraction =
        static_cast<float>(timing_.channel_offset_us[c] / timing_.block_period_us);
    channels_[c].azimuth_offset_units = static_cast<int>(std::lround(-rot_correction * kRadToUnits));
  }
  content_.mode = options.return_mode;
  content_.product_id = ProductIdOf(options.model);
}

DataPacketSimulator::SensorPose DataPacketSimulator::SensorPoseAt(TimeNs drive_time_ns) const {
  const Eigen::Isometry3d world_T_sensor =
      trajectory_->At(NsToSeconds(drive_time_ns)).world_T_vehicle * options_.vehicle_T_sensor;
  return {world_T_sensor.linear(), world_T_sensor.translation()};
}

// Poses at packet boundaries; consecutive packets share one, so each costs one At().
void DataPacketSimulator::UpdateMotion(std::uint64_t k) {
  if (k == motion_packet_) return;
  const SensorPose start = k == motion_packet_ + 1 ? next_start_ : SensorPoseAt(FirstFiringNs(k));
  next_start_ = SensorPoseAt(FirstFiringNs(k + 1));
  motion_.start = start;
  motion_.delta = {next_start_.rotation - start.rotation, next_start_.translation - start.translation};
  motion_packet_ = k;
}

// Azimuth of each block's firing: the head turns at rotation_hz from start_azimuth_deg.
void DataPacketSimulator::FillBlockAzimuths(TimeNs first_firing_ns) {
  for (std::size_t block = 0; block < kBlocksPerPacket; ++block) {
    const int firing = schedule_.FiringOfBlock(static_cast<int>(block));
    const TimeNs t_ns = first_firing_ns + firing * block_period_ns_;
    const double turns = options_.start_azimuth_deg / 360.0 + options_.rotation_hz * NsToSeconds(t_ns);
    const double fraction = turns - std::floor(turns);
    const long units = std::lround(fraction * kUnitsPerTurn) % kUnitsPerTurn;
    content_.block_azimuth_units[block] = static_cast<std::uint16_t>(units);
  }
}

// PacketDecoder::AzimuthGapUnits: the gap to the next firing in the packet; the last
// firing reuses the previous gap.
std::array<int, kBlocksPerPacket> DataPacketSimulator::DecoderAzimuthGaps() const {
  const int step = options_.return_mode == velodyne::ReturnMode::kDual ? 2 : 1;
  std::array<int, kBlocksPerPacket> gaps{};
  int last_gap = 0;
  for (int block = 0; block < static_cast<int>(kBlocksPerPacket); ++block) {
    const int next = block + step;
    if (next < static_cast<int>(kBlocksPerPacket)) {
      last_gap = WrapUnits(content_.block_azimuth_units[static_cast<std::size_t>(next)] -
                           content_.block_azimuth_units[static_cast<std::size_t>(block)]);
    }
    gaps[static_cast<std::size_t>(block)] = last_gap;
  }
  return gaps;
}

void DataPacketSimulator::Simulate(std::uint64_t k, velodyne::DataPacketBytes& out) {
  const TimeNs start_ns = FirstFiringNs(k);
  UpdateMotion(k);
  FillBlockAzimuths(start_ns);
  const TimeNs unix_ns = options_.start_epoch_ns + start_ns;
  content_.us_past_hour = static_cast<std::uint32_t>((unix_ns % kNsPerHour) / kNsPerUs);
  const std::array<int, kBlocksPerPacket> gaps = DecoderAzimuthGaps();
  for (int block = 0; block < static_cast<int>(kBlocksPerPacket); ++block) {
    const auto b = static_cast<std::size_t>(block);
    if (block > 0 && schedule_.FiringOfBlock(block) == schedule_.FiringOfBlock(block - 1)) {
      content_.records[b] = content_.records[b - 1];  // dual return: one surface, one return
      continue;
    }
    SimulateBlock(k, block, gaps[b], start_ns);
  }
  Result<velodyne::DataPacketBytes> encoded = velodyne::EncodeDataPacket(content_);
  assert(encoded.ok());  // azimuths, mode and timestamp are valid by construction
  out = *encoded;
}

void DataPacketSimulator::SimulateBlock(std::uint64_t k, int block, int gap_units,
                                        TimeNs packet_start_ns) {
  const auto b = static_cast<std::size_t>(block);
  const float gap = static_cast<float>(gap_units);
  const int block_azimuth = content_.block_azimuth_units[b];
  std::array<double, kChannelsPerBlock> ranges{};  // true ranges; < 0: nothing within max range
  for (std::size_t c = 0; c < kChannelsPerBlock; ++c) {
    const ChannelConstants& channel = channels_[c];
    const int azimuth = WrapUnits(block_azimuth + static_cast<int>(gap * channel.block_fraction + 0.5f) +
                                  channel.azimuth_offset_units);
    const std::optional<SurfaceHit> hit = CastRay(block, static_cast<int>(c), azimuth, packet_start_ns);
    ranges[c] = hit ? hit->range_m : -1.0;
    content_.records[b][c].reflectivity = hit ? hit->reflectivity : 0;
  }
  MeasureRanges(k, block, ranges);
}

// Dropouts, noise and range limits. One draw per pair of channels gives both channels'
// noise (Box-Muller's two outputs) and, re-mixed, their dropout uniforms.
void DataPacketSimulator::MeasureRanges(std::uint64_t k, int block,
                                        const std::array<double, kChannelsPerBlock>& ranges) {
  const auto firing = static_cast<std::uint64_t>(schedule_.FiringOfBlock(block));
  const double sigma = options_.range_noise_sigma_m;
  const double dropout = options_.dropout_probability;
  std::array<velodyne::ChannelRecord, kChannelsPerBlock>& records = content_.records[static_cast<std::size_t>(block)];
  for (std::size_t pair = 0; pair < kChannelsPerBlock / 2; ++pair) {
    const std::uint64_t bits = HashKey(seed_ ^ kRangeStream, k, firing, pair);
    std::array<double, 2> noise{};
    if (sigma > 0.0 && (ranges[2 * pair] >= 0.0 || ranges[2 * pair + 1] >= 0.0)) {
      noise = NormalPairFromBits(bits);
    }
    for (std::size_t i = 0; i < 2; ++i) {
      const std::size_t c = 2 * pair + i;
      const double range = ranges[c] + sigma * noise[i];
      const bool dropped = dropout > 0.0 && UniformFromBits(MixBits(bits + 1 + i)) < dropout;
      if (ranges[c] < 0.0 || dropped || range < options_.min_range_m || range > options_.max_range_m) {
        records[c] = {};
        continue;
      }
      records[c].distance_units =
          velodyne::RawDistance(range, table_, schedule_.At(block, static_cast<int>(c)).laser_id);
    }
  }
}

std::optional<SurfaceHit> DataPacketSimulator::CastRay(int block, int channel, int azimuth_units,
                                                       TimeNs packet_start_ns) const {
  const velodyne::ChannelFiring& firing = schedule_.At(block, channel);
  const LaserGeometry& laser = lasers_[static_cast<std::size_t>(firing.laser_id)];
  const double cos_azimuth = cos_table_[static_cast<std::size_t>(azimuth_units)];
  const double sin_azimuth = sin_table_[static_cast<std::size_t>(azimuth_units)];
  // The decoder's point is origin + range x direction (packet_decoder.cpp, manuals 9.2).
  const Eigen::Vector3d direction_sensor(laser.cos_elevation * cos_azimuth,
                                         -laser.cos_elevation * sin_azimuth, laser.sin_elevation);
  const double lever = laser.vertical_offset_m * laser.sin_elevation;
  const Eigen::Vector3d origin_sensor(-lever * cos_azimuth + laser.horizontal_offset_m * sin_azimuth,
                                      lever * sin_azimuth + laser.horizontal_offset_m * cos_azimuth,
                                      laser.vertical_offset_m * laser.cos_elevation);

  const double time_offset_ns = firing.time_offset_us * 1e3;
  const double s = time_offset_ns / static_cast<double>(packet_period_ns_);
  const Eigen::Matrix3d rotation = motion_.start.rotation + s * motion_.delta.rotation;
  const Eigen::Vector3d translation = motion_.start.translation + s * motion_.delta.translation;
  const Eigen::Vector3d direction = (rotation * direction_sensor).normalized();
  const Eigen::Vector3d origin = rotation * origin_sensor + translation;
  const double world_time_s =
      (static_cast<double>(packet_start_ns) + time_offset_ns) * 1e-9 + world_time_offset_s_;
  return scene_->Cast(origin, direction, options_.max_range_m, world_time_s);
}

}  // namespace flat2d::hal::sim
