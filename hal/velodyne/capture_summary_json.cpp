#include "hal/velodyne/capture_summary_json.hpp"

#include <cstdio>
#include <sstream>

namespace flat2d::hal::velodyne {
namespace {

std::string Quote(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string Seconds(TimeNs ns) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6f", static_cast<double>(ns) * 1e-9);
  return buffer;
}

void WriteIdentification(std::ostringstream& out, const CaptureSummary& summary) {
  const auto& id = summary.identification;
  out << "\"product\":" << Quote(summary.product) << ",";
  out << "\"supported\":" << (id ? "true" : "false") << ",";
  if (summary.model_error) out << "\"error\":" << Quote(summary.model_error->message) << ",";
  if (!id) return;
  out << "\"return_mode\":" << Quote(std::string(ReturnModeName(id->return_mode))) << ",";
  out << "\"product_id\":" << static_cast<int>(id->product_id) << ",";
  out << "\"model_decided_by\":" << Quote(id->decided_by) << ",";
  if (id->packet_period_us) out << "\"packet_period_us\":" << *id->packet_period_us << ",";
  out << "\"disagreements\":[";
  for (std::size_t i = 0; i < id->disagreements.size(); ++i) {
    out << (i ? "," : "") << Quote(id->disagreements[i]);
  }
  out << "],";
}

void WriteCounts(std::ostringstream& out, const CaptureSummary& summary) {
  const VelodyneStreamStats& s = summary.stream;
  out << "\"data_packets\":" << s.data_packets << ",\"position_packets\":" << s.position_packets
      << ",\"revolutions\":" << s.revolutions << ",\"partial_revolutions\":" << s.partial_revolutions
      << ",\"points\":" << s.points << ",\"malformed\":" << (s.malformed + summary.capture.malformed)
      << ",\"malformed_detail\":{\"wrong_size\":" << s.wrong_size
      << ",\"bad_block_flag\":" << s.bad_block_flag << ",\"bad_azimuth\":" << s.bad_azimuth
      << ",\"unknown_return_mode\":" << s.unknown_return_mode
      << ",\"bad_position_packets\":" << s.bad_position_packets
      << ",\"bad_frames\":" << summary.capture.malformed << "}"
      << ",\"undecodable_packets\":" << s.undecodable_model << ",\"out_of_order\":" << s.out_of_order
      << ",\"lost_packets\":" << s.lost_packets << ",\"pauses\":" << s.pauses
      << ",\"dropped_fans\":" << s.dropped_fans << ",\"ignored_datagrams\":" << s.ignored << ",";
  const net::CaptureStats& c = summary.capture;
  out << "\"capture\":{\"frames\":" << c.frames << ",\"udp_datagrams\":" << c.udp_datagrams
      << ",\"non_udp\":" << c.non_udp << ",\"fragments\":" << c.fragments
      << ",\"truncated_frames\":" << c.truncated_frames
      << ",\"ipv4_length_overruns\":" << c.ipv4_length_overruns
      << ",\"file_truncated\":" << (c.file_truncated ? "true" : "false");
  if (c.file_truncated) out << ",\"file_error\":" << Quote(c.file_error);
  out << "},";
}

void WriteRevolutions(std::ostringstream& out, const CaptureSummary& summary) {
  out << "\"revolution_list\":[";
  for (std::size_t i = 0; i < summary.revolutions.size(); ++i) {
    const RevolutionSummary& r = summary.revolutions[i];
    out << (i ? "," : "") << "{\"complete\":" << (r.complete ? "true" : "false")
        << ",\"fans\":" << r.fans << ",\"points\":" << r.points
        << ",\"start_s\":" << Seconds(r.start_ns) << ",\"end_s\":" << Seconds(r.end_ns)
        << ",\"swept_deg\":" << r.swept_azimuth_deg << ",\"max_range_m\":" << r.max_range_m << "}";
  }
  out << "]";
}

}  // namespace

std::string CaptureSummaryToJson(const CaptureSummary& summary, const std::string& capture_path) {
  std::ostringstream out;
  out.precision(10);
  out << "{\"file\":" << Quote(capture_path) << ",";
  WriteIdentification(out, summary);
  WriteCounts(out, summary);
  out << "\"time_source\":" << Quote(std::string(TimeSourceName(summary.time_source))) << ",";
  if (summary.last_position && summary.last_position->rmc) {
    out << "\"gps_fix\":{\"utc_s\":" << Seconds(summary.last_position->rmc->utc_time_ns)
        << ",\"nmea\":" << Quote(std::string(summary.last_position->nmea_sentence())) << "},";
  }
  WriteRevolutions(out, summary);
  out << "}";
  return out.str();
}

}  // namespace flat2d::hal::velodyne
