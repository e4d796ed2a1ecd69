// Runs a real CAN log through CanOdometry with a shipped configuration, for the real-drive
// tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "hal/can/candump_log.hpp"
#include "localization/odometry/can_odometry.hpp"
#include "localization/odometry/odometry_config.hpp"

namespace flat2d::localization::test {

inline constexpr double kRadToDeg = 180.0 / std::numbers::pi;
inline constexpr char kRav4Dbc[] = "can/toyota_rav4h_comma2k19/toyota_rav4_hybrid_2017_pt_generated.dbc";
inline constexpr char kRav4Log[] = "can/toyota_rav4h_comma2k19/DERIVED_comma2k19_rav4h_seg40_bus0.candump.log";
inline constexpr char kComma[] = "can/toyota_rav4h_comma2k19/b0c9d2329ad1606b_2018-08-02--08-34-47_seg40/";

inline std::filesystem::path ShippedConfig(const char* name) {
  return std::filesystem::path(FLAT2D_SOURCE_DIR) / "packaging/config/odometry" / name;
}

// Every sample of a log run through CanOdometry, with what the mapper decoded.
struct LogRun {
  std::vector<OdometrySample> samples;
  std::vector<hal::can::OdometryMeasurement> measurements;
  hal::can::FrameDecoderStats decoder;
  DeadReckoningStats dead_reckoning;
  double yaw_rate_bias_radps = 0.0;  // configured or learnt, at the end
};

inline LogRun RunLog(const std::filesystem::path& dbc_path, const std::filesystem::path& log_path,
           OdometryConfig config) {
  LogRun run;
  auto dbc = hal::can::LoadDbc(dbc_path);
  EXPECT_TRUE(dbc.ok()) << (dbc.ok() ? "" : dbc.error().message);
  auto odometry = dbc.ok() ? CanOdometry::Create(*dbc, config) : Result<CanOdometry>(dbc.error());
  EXPECT_TRUE(odometry.ok()) << (odometry.ok() ? "" : odometry.error().message);
  auto reader = hal::can::CandumpReader::Open(log_path);
  EXPECT_TRUE(reader.ok());
  if (!odometry.ok() || !reader.ok()) return run;
  hal::can::CanFrame frame;
  while (reader->Next(frame)) {
    const auto update = odometry->Push(frame);
    if (!update) continue;
    run.measurements.push_back(odometry->last_measurement());
    if (update->new_sample()) run.samples.push_back(update->sample);
  }
  run.decoder = odometry->mapper().decoder_stats();
  run.dead_reckoning = odometry->dead_reckoning().stats();
  run.yaw_rate_bias_radps = odometry->dead_reckoning().yaw_rate_bias_radps();
  return run;
}

inline OdometryConfig LoadShipped(const char* name) {
  auto config = LoadOdometryConfig(ShippedConfig(name));
  EXPECT_TRUE(config.ok()) << (config.ok() ? "" : config.error().message);
  return config.ok() ? *config : OdometryConfig{};
}

inline double PathLength(const std::vector<OdometrySample>& samples, TimeNs from, TimeNs to) {
  double length = 0.0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i - 1].time_ns < from || samples[i].time_ns > to) continue;
    length += (samples[i].local_T_vehicle.translation() - samples[i - 1].local_T_vehicle.translation()).norm();
  }
  return length;
}

}  // namespace flat2d::localization::test
