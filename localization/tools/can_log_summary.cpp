#include "localization/tools/can_log_summary.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "hal/can/dbc.hpp"
#include "localization/odometry/can_odometry.hpp"
#include "localization/tools/odometry_poses.hpp"
#include "localization/odometry/odometry_config.hpp"

namespace flat2d::localization {
namespace {

using hal::can::CanFrame;

// "SIGNAL" or "MESSAGE.SIGNAL" to selections; a bare signal name may match several messages.
Result<std::vector<hal::can::SignalSelection>> Select(const hal::can::Dbc& dbc,
                                                      const std::vector<std::string>& names) {
  if (names.empty()) return hal::can::AllSignals(dbc);
  std::vector<hal::can::SignalSelection> selection;
  for (const std::string& name : names) {
    const auto dot = name.find('.');
    const std::string message = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string signal = dot == std::string::npos ? name : name.substr(dot + 1);
    const std::size_t before = selection.size();
    for (const hal::can::DbcMessage& m : dbc.messages) {
      if ((message.empty() || m.name == message) && m.FindSignal(signal) != nullptr) {
        selection.push_back({m.name, signal});
      }
    }
    if (selection.size() == before) return MakeError("--signals: no signal '" + name + "' in " + dbc.source);
  }
  return selection;
}

void Count(CanLogSummary& summary, const CanFrame& frame) {
  if (summary.frames_per_id.empty() || frame.time_ns < summary.first_ns) summary.first_ns = frame.time_ns;
  summary.last_ns = std::max(summary.last_ns, frame.time_ns);
  ++summary.frames_per_id[frame.id | (frame.extended ? 0x80000000u : 0u)];
}

void WriteCsvRows(const hal::can::FrameDecoder& decoder, const std::vector<hal::can::SignalSelection>& selection,
                  const CanFrame& frame, std::ostream& csv) {
  char line[256];
  for (const std::size_t slot : decoder.updated()) {
    const auto& s = selection[slot];
    std::snprintf(line, sizeof(line), "%.6f,%s,%s,%.10g\n", static_cast<double>(frame.time_ns) * 1e-9,
                  s.message.c_str(), s.signal.c_str(), decoder.values()[slot].value);
    csv << line;
  }
}

}  // namespace

Result<CanLogSummary> DecodeCanLog(const std::filesystem::path& dbc_path, const std::filesystem::path& log_path,
                                   const std::vector<std::string>& signals, std::ostream* csv) {
  Result<hal::can::Dbc> dbc = hal::can::LoadDbc(dbc_path);
  if (!dbc.ok()) return dbc.error();
  Result<std::vector<hal::can::SignalSelection>> selection = Select(*dbc, signals);
  if (!selection.ok()) return selection.error();
  Result<hal::can::FrameDecoder> decoder = hal::can::FrameDecoder::Create(*dbc, *selection);
  if (!decoder.ok()) return decoder.error();
  Result<hal::can::CandumpReader> reader = hal::can::CandumpReader::Open(log_path);
  if (!reader.ok()) return reader.error();

  CanLogSummary summary;
  if (csv != nullptr) *csv << "time,message,signal,value\n";
  CanFrame frame;
  while (reader->Next(frame)) {
    Count(summary, frame);
    if (decoder->Decode(frame) == hal::can::FrameStatus::kDecoded && csv != nullptr) {
      WriteCsvRows(*decoder, *selection, frame, *csv);
    }
  }
  summary.log = reader->stats();
  summary.decoder = decoder->stats();
  return summary;
}

Result<CanLogSummary> DeadReckonCanLog(const std::filesystem::path& dbc_path, const std::filesystem::path& config_path,
                                       const std::filesystem::path& log_path, std::ostream& tum) {
  Result<CanLogOdometry> opened = OpenCanLogOdometry(dbc_path, config_path, log_path);
  if (!opened.ok()) return opened.error();
  CanOdometry* odometry = &opened->odometry;
  hal::can::CandumpReader* reader = &opened->reader;

  CanLogSummary summary;
  CanFrame frame;
  char line[256];
  while (reader->Next(frame)) {
    Count(summary, frame);
    const auto update = odometry->Push(frame);
    if (!update) continue;
    ++summary.measurements;
    if (!update->new_sample()) continue;
    const OdometrySample& sample = update->sample;
    if (summary.final_sample) {
      summary.distance_m += (sample.local_T_vehicle.translation() - summary.final_sample->local_T_vehicle.translation()).norm();
    }
    const double theta = sample.local_T_vehicle.theta();
    std::snprintf(line, sizeof(line), "%.9f %.6f %.6f 0 0 0 %.9f %.9f\n",
                  static_cast<double>(sample.time_ns) * 1e-9, sample.local_T_vehicle.x(),
                  sample.local_T_vehicle.y(), std::sin(theta / 2.0), std::cos(theta / 2.0));
    tum << line;
    summary.final_sample = sample;
    ++summary.samples;
  }
  summary.log = reader->stats();
  summary.decoder = odometry->mapper().decoder_stats();
  summary.dead_reckoning = odometry->dead_reckoning().stats();
  summary.yaw_rate_bias_radps = odometry->dead_reckoning().yaw_rate_bias_radps();
  return summary;
}

std::string CanLogSummaryToJson(const CanLogSummary& summary, bool odometry) {
  std::ostringstream out;
  out.precision(10);
  out << "{\"frames\":" << summary.log.frames << ",\"lines\":" << summary.log.lines
      << ",\"malformed_lines\":" << summary.log.malformed << ",\"first_malformed_lines\":[";
  for (std::size_t i = 0; i < summary.log.first_malformed.size(); ++i) {
    out << (i ? "," : "") << summary.log.first_malformed[i].line;
  }
  out << "],\"error_frames\":" << summary.log.error_frames
      << ",\"duration_s\":" << static_cast<double>(summary.last_ns - summary.first_ns) * 1e-9
      << ",\"first_time_s\":" << static_cast<double>(summary.first_ns) * 1e-9
      << ",\"decoded_frames\":" << summary.decoder.decoded
      << ",\"checksum_checked\":" << summary.decoder.checksum_checked
      << ",\"checksum_failures\":" << summary.decoder.checksum_failures
      << ",\"too_short\":" << summary.decoder.too_short << ",\"frames_per_id\":{";
  bool first = true;
  for (const auto& [key, count] : summary.frames_per_id) {
    char id[16];
    std::snprintf(id, sizeof(id), (key & 0x80000000u) ? "%08" PRIX32 : "%03" PRIX32, key & 0x1FFFFFFFu);
    out << (first ? "" : ",") << "\"" << id << "\":" << count;
    first = false;
  }
  out << "}";
  if (odometry) {
    out << ",\"measurements\":" << summary.measurements << ",\"samples\":" << summary.samples
        << ",\"distance_m\":" << summary.distance_m
        << ",\"yaw_rate_bias_radps\":" << summary.yaw_rate_bias_radps
        << ",\"gaps\":" << summary.dead_reckoning.gaps
        << ",\"out_of_order\":" << summary.dead_reckoning.out_of_order;
    if (summary.final_sample) {
      const auto& pose = summary.final_sample->local_T_vehicle;
      out << ",\"final_pose\":{\"x\":" << pose.x() << ",\"y\":" << pose.y() << ",\"theta\":" << pose.theta()
          << "}";
    }
  }
  out << "}";
  return out.str();
}

}  // namespace flat2d::localization
