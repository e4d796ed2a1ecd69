// Real CAN logs of other vehicles through the shipped odometry configurations, checked for
// physical plausibility (the RAV4 drive with its reference is can_odometry_real_test.cpp).
#include <cstdio>

#include <gtest/gtest.h>

#include "tests/localization/odometry/can_log_run.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::localization {
namespace {

using namespace test;

// Every shipped odometry configuration parses and gives valid options.
TEST(CanOdometryReal, ShippedConfigurationsAreValid) {
  int configs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(ShippedConfig(""))) {
    if (entry.path().extension() != ".textproto") continue;
    auto config = LoadOdometryConfig(entry.path());
    EXPECT_TRUE(config.ok()) << entry.path() << ": " << (config.ok() ? "" : config.error().message);
    ++configs;
  }
  EXPECT_GE(configs, 2);
}

// A second Toyota (strym's RAV4 2019 DBC) on a surface-street drive with stops: the same
// shipped mapping decodes it, checksums hold, and the yaw-rate bias is learnt at the stops.
TEST(CanOdometryReal, VerifiedCanToyotaDriveIsPlausible) {
  FLAT2D_REQUIRE_DATA(dbc, "can/toyota_verifiedcan/strym_toyota_rav4_2019.dbc");
  FLAT2D_REQUIRE_DATA(log, "can/toyota_verifiedcan/DERIVED_verifiedcan_toyota_2020-02-03-14-31-11.candump.log");
  const LogRun run = RunLog(dbc, log, LoadShipped("toyota_rav4_hybrid_2017.textproto"));
  EXPECT_EQ(run.decoder.checksum_failures, 0u);
  EXPECT_EQ(run.decoder.checksum_checked, 1527u + 2703u + 1202u);
  double top_speed = 0.0, rear_integral = 0.0, previous_t = -1.0, previous_rear = 0.0;
  for (const auto& m : run.measurements) {
    if (!m.wheel_speeds) continue;
    const auto& w = *m.wheel_speeds;
    for (double v : {w.front_left_mps, w.front_right_mps, w.rear_left_mps, w.rear_right_mps}) {
      EXPECT_GE(v, 0.0);
      top_speed = std::max(top_speed, v);
    }
    const double t = static_cast<double>(m.time_ns) * 1e-9;
    const double rear = 0.5 * (w.rear_left_mps + w.rear_right_mps);
    if (previous_t >= 0.0 && t - previous_t < 0.2) rear_integral += 0.5 * (previous_rear + rear) * (t - previous_t);
    previous_t = t;
    previous_rear = rear;
  }
  const double distance = PathLength(run.samples, run.samples.front().time_ns, run.samples.back().time_ns);
  std::printf("VerifiedCAN Toyota: top wheel speed %.1f km/h, distance %.1f m (rear-wheel integral %.1f m), "
              "%llu standstill steps, yaw-rate bias learnt %.3f deg/s, %llu gaps\n",
              top_speed * 3.6, distance, rear_integral,
              static_cast<unsigned long long>(run.dead_reckoning.standstill_steps),
              run.yaw_rate_bias_radps * kRadToDeg,
              static_cast<unsigned long long>(run.dead_reckoning.gaps));
  EXPECT_NEAR(top_speed * 3.6, 47.1, 0.5);  // PROVENANCE.md: wheel speeds 0-47.1 km/h
  EXPECT_GT(run.dead_reckoning.standstill_steps, 0u);
  EXPECT_GT(run.dead_reckoning.bias_updates, 0u);
  EXPECT_NEAR(distance / rear_integral, 1.0, 0.02);
}

// The Honda FK8: wheel speeds only, heading from the wheels, Honda checksums verified.
TEST(CanOdometryReal, CivicDriveIsPlausible) {
  FLAT2D_REQUIRE_DATA(dbc, "can/eldominio_candump/honda_civic_hatchback_ex_2017_can_generated.dbc");
  FLAT2D_REQUIRE_DATA(log, "can/eldominio_candump/civic_19_type_r__turnonanddrive.log");
  const LogRun run = RunLog(dbc, log, LoadShipped("honda_civic_2017.textproto"));
  EXPECT_EQ(run.decoder.checksum_checked, 803u);
  EXPECT_EQ(run.decoder.checksum_failures, 0u);
  double top_speed = 0.0;
  std::size_t sets = 0;
  for (const auto& m : run.measurements) {
    if (!m.wheel_speeds) continue;
    ++sets;
    for (double v : {m.wheel_speeds->front_left_mps, m.wheel_speeds->front_right_mps,
                     m.wheel_speeds->rear_left_mps, m.wheel_speeds->rear_right_mps}) {
      EXPECT_GE(v, 0.0);
      top_speed = std::max(top_speed, v);
    }
  }
  const double distance = PathLength(run.samples, run.samples.front().time_ns, run.samples.back().time_ns);
  std::printf("Civic: %zu wheel-speed sets, top %.2f km/h, distance %.1f m, heading change %.1f deg\n", sets,
              top_speed * 3.6, distance, run.samples.back().local_T_vehicle.theta() * kRadToDeg);
  EXPECT_EQ(sets, 803u);
  EXPECT_NEAR(top_speed * 3.6, 9.6, 0.1);  // PROVENANCE.md: 0-9.6 km/h on all four wheels
  EXPECT_GT(distance, 1.0);
  EXPECT_LT(distance, 9.6 / 3.6 * 65.5);  // never faster than the top speed
}

// The Scion xB log is heavily decimated and its wheel speeds are in no DBC we have: only
// SPEED (0xB4) decodes with the Toyota DBC. A speed-only configuration dead-reckons it
// straight ahead, and SPEED's checksum holds.
TEST(CanOdometryReal, ScionSpeedOnlyLogIsPlausible) {
  FLAT2D_REQUIRE_DATA(dbc, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log, "can/eldominio_candump/xb__trymph.log");
  OdometryConfig config;
  auto* speed = config.mutable_mapping()->mutable_vehicle_speed();
  speed->set_message("SPEED");
  speed->set_signal("SPEED");
  speed->set_unit("km/h");
  config.mutable_dead_reckoning()->set_wheel_base_m(2.63);
  config.mutable_dead_reckoning()->set_track_m(1.49);
  config.mutable_dead_reckoning()->set_max_gap_s(1.0);
  const LogRun run = RunLog(dbc, log, config);
  double top_speed = 0.0;
  for (const auto& m : run.measurements) {
    if (!m.vehicle_speed_mps) continue;
    EXPECT_GE(*m.vehicle_speed_mps, 0.0);
    top_speed = std::max(top_speed, *m.vehicle_speed_mps);
  }
  std::printf("Scion xB: %zu SPEED frames, top %.2f km/h, %llu checksums checked, %llu gaps\n",
              run.measurements.size(), top_speed * 3.6,
              static_cast<unsigned long long>(run.decoder.checksum_checked),
              static_cast<unsigned long long>(run.dead_reckoning.gaps));
  EXPECT_NEAR(top_speed * 3.6, 94.55, 0.01);  // PROVENANCE.md: SPEED 0-94.55 km/h
  EXPECT_EQ(run.decoder.checksum_failures, 0u);
  EXPECT_EQ(run.decoder.checksum_checked, run.measurements.size());
  EXPECT_NEAR(run.samples.back().local_T_vehicle.theta(), 0.0, 1e-12);  // no yaw source
}

}  // namespace
}  // namespace flat2d::localization
