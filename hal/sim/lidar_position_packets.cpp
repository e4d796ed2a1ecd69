#include "hal/sim/lidar_position_packets.hpp"

#include <cassert>
#include <cmath>

#include "hal/common/angles.hpp"
#include "hal/sim/georeference.hpp"
#include "hal/sim/stateless_random.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr std::uint64_t kGnssStream = 0x474E5353ULL;  // "GNSS"

// The HDL-32E capture's Garmin: "220243", "3708.5809", "028.8", "158.3".
velodyne::RmcFormat GarminFormat() {
  velodyne::RmcFormat format;
  format.time_decimals = 0;
  format.minute_decimals = 4;
  format.speed_digits = 3;
  format.course_digits = 3;
  format.variation_digits = 3;
  return format;
}

TimeNs FloorDiv(TimeNs a, TimeNs b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// True course: clockwise from north, in [0, 360), of the vehicle's x axis (world x east).
double CourseDeg(const Eigen::Isometry3d& world_T_vehicle) {
  const Eigen::Vector3d forward = world_T_vehicle.linear().col(0);
  const double course = std::atan2(forward.x(), forward.y()) * kRadToDeg;
  return course < 0.0 ? course + 360.0 : course;
}

}  // namespace

PositionPacketSimulator::PositionPacketSimulator(const Trajectory& trajectory,
                                                 const LidarOptions& options, std::uint64_t seed)
    : trajectory_(&trajectory),
      options_(options),
      seed_(seed),
      period_ns_(std::llround(options.position_period_us * 1e3)),
      sentence_latency_ns_(std::llround(options.gnss.sentence_latency_s * 1e9)),
      format_(options.model == velodyne::Model::kHdl32e && !options.gnss.rtk ? GarminFormat()
                                                                            : velodyne::RmcFormat{}),
      pps_status_(options.gnss.enabled && options.model != velodyne::Model::kHdl32e
                      ? velodyne::PpsStatus::kLocked
                      : velodyne::PpsStatus::kAbsent) {}

TimeNs PositionPacketSimulator::AssemblyTimeNs(std::uint64_t j) const {
  return static_cast<TimeNs>(j) * period_ns_ + period_ns_ / 2;
}

velodyne::RmcFix PositionPacketSimulator::FixOfSecond(std::int64_t unix_second) const {
  velodyne::RmcFix fix;
  fix.utc_time_ns = unix_second * kNsPerSecond;
  fix.has_time = true;
  if (!options_.gnss.enabled) {
    fix.status = 'V';
    fix.mode = 'N';
    return fix;
  }
  const TimeNs drive_ns = fix.utc_time_ns - options_.start_epoch_ns;
  const VehicleState state = trajectory_->At(static_cast<double>(drive_ns) * 1e-9);
  const auto key = static_cast<std::uint64_t>(unix_second);
  const double sigma = options_.gnss.rtk ? options_.gnss.rtk_sigma_m : options_.gnss.horizontal_sigma_m;
  const Eigen::Vector2d error(sigma * NormalFromBits(HashKey(seed_ ^ kGnssStream, key, 0)),
                              sigma * NormalFromBits(HashKey(seed_ ^ kGnssStream, key, 1)));
  const LatLon position =
      LocalToGeodetic(options_.gnss.origin, state.world_T_vehicle.translation().head<2>() + error);
  fix.has_position = true;
  fix.latitude_deg = position.latitude_deg;
  fix.longitude_deg = position.longitude_deg;
  fix.speed_mps = state.speed_mps;
  fix.course_deg = CourseDeg(state.world_T_vehicle);
  fix.status = 'A';
  fix.mode = 'A';
  fix.valid = true;
  return fix;
}

void PositionPacketSimulator::Simulate(std::uint64_t j, velodyne::PositionPacketBytes& out) const {
  const TimeNs unix_ns = options_.start_epoch_ns + AssemblyTimeNs(j);
  velodyne::PositionPacketContent content;
  content.us_past_hour = static_cast<std::uint32_t>((unix_ns % kNsPerHour) / kNsPerUs);
  content.pps_status = pps_status_;
  // Without a receiver the sentence region stays NUL, as the real captures without GPS show.
  if (options_.gnss.enabled) {
    content.rmc = FixOfSecond(FloorDiv(unix_ns - sentence_latency_ns_, kNsPerSecond));
  }
  content.format = format_;
  Result<velodyne::PositionPacketBytes> encoded = velodyne::EncodePositionPacket(content);
  assert(encoded.ok());  // times after 1980, positions on the globe by construction
  out = *encoded;
}

}  // namespace flat2d::hal::sim
