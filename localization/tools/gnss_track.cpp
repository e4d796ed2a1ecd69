#include "localization/tools/gnss_track.hpp"

#include "hal/net/datagram_source.hpp"
#include "hal/sim/georeference.hpp"
#include "hal/velodyne/position_packet.hpp"

namespace flat2d::localization {

Result<std::vector<evaluation::TimedPose>> ReadGnssTrack(const std::filesystem::path& capture,
                                                         GnssTrackStats* stats) {
  auto source = hal::net::OpenCapture(capture);
  if (!source.ok()) return source.error();
  GnssTrackStats counts;
  std::vector<evaluation::TimedPose> track;
  hal::sim::GeoOrigin origin;
  TimeNs last_fix_ns = 0;
  while (auto datagram = (*source)->Next()) {
    if (datagram->payload.size() != hal::velodyne::kPositionPacketSize) continue;
    ++counts.position_packets;
    const auto packet = hal::velodyne::DecodePositionPacket(datagram->payload);
    if (!packet.ok()) {
      ++counts.malformed;
      continue;
    }
    if (!packet->rmc) continue;  // no receiver attached
    const hal::velodyne::RmcFix& fix = *packet->rmc;
    if (!fix.valid || !fix.has_position || !fix.has_time) {
      ++counts.void_fixes;
      continue;
    }
    // The packets repeat a sentence until the next fix arrives.
    if (!track.empty() && fix.utc_time_ns <= last_fix_ns) continue;
    if (track.empty()) origin = {fix.latitude_deg, fix.longitude_deg};
    last_fix_ns = fix.utc_time_ns;
    const Eigen::Vector2d east_north = hal::sim::GeodeticToLocal(origin, {fix.latitude_deg, fix.longitude_deg});
    track.push_back({static_cast<double>(fix.utc_time_ns) * 1e-9, Se2(east_north, 0.0)});
  }
  if (stats != nullptr) *stats = counts;
  return track;
}

}  // namespace flat2d::localization
