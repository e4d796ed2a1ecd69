// The work behind `flat2d-can`: decode a candump log with a DBC (CSV rows or a summary),
// and dead-reckon it with an odometry configuration (TUM trajectory and a summary).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "hal/can/candump_log.hpp"
#include "hal/can/frame_decoder.hpp"
#include "hal/common/error.hpp"
#include "localization/odometry/dead_reckoning.hpp"

namespace flat2d::localization {

struct CanLogSummary {
  hal::can::CandumpReaderStats log;
  hal::can::FrameDecoderStats decoder;
  std::map<std::uint32_t, std::uint64_t> frames_per_id;  // key: id | 0x80000000 if extended
  TimeNs first_ns = 0;
  TimeNs last_ns = 0;
  // Odometry runs only:
  std::uint64_t measurements = 0;
  std::uint64_t samples = 0;
  double distance_m = 0.0;
  std::optional<OdometrySample> final_sample;
  DeadReckoningStats dead_reckoning;
  double yaw_rate_bias_radps = 0.0;
};

// Decodes every frame of `log`; with `csv`, writes "time,message,signal,value" rows for
// the selected signals ("SIGNAL" or "MESSAGE.SIGNAL"; empty: all of the DBC).
Result<CanLogSummary> DecodeCanLog(const std::filesystem::path& dbc, const std::filesystem::path& log,
                                   const std::vector<std::string>& signals, std::ostream* csv);

// Dead-reckons `log`; writes every new sample to `tum` as "t x y z qx qy qz qw".
Result<CanLogSummary> DeadReckonCanLog(const std::filesystem::path& dbc, const std::filesystem::path& config,
                                       const std::filesystem::path& log, std::ostream& tum);

// One JSON object with the summary's counts (keys: frames, frames_per_id, malformed_lines,
// checksum_failures, duration_s, and more).
std::string CanLogSummaryToJson(const CanLogSummary& summary, bool odometry);

}  // namespace flat2d::localization
