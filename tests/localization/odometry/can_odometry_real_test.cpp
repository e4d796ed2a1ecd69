// Real vehicle CAN logs through the shipped odometry configurations, checked for what
// could be wrong: against comma2k19's own decode and GNSS-fused trajectory of the same RAV4
// drive (other vehicles: can_odometry_vehicles_test.cpp). Figures are printed so the
// closing notes can quote them.
#include "localization/odometry/can_odometry.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "tests/localization/odometry/can_log_run.hpp"
#include "tests/testing/data_path.hpp"
#include "tests/testing/npy.hpp"

namespace flat2d::localization {
namespace {

using namespace test;

// comma's fused trajectory: times, path length, and course (direction of the velocity,
// counter-clockwise from east) unwrapped, in a local east-north frame at the first pose.
struct Fused {
  std::vector<double> t;
  std::vector<double> course;
  double path_length = 0.0;
};

std::optional<Fused> LoadFused() {
  const auto times = testing::ReadNpyFloat64(testing::DataRoot() / kComma / "global_pose/frame_times");
  const auto positions = testing::ReadNpyFloat64(testing::DataRoot() / kComma / "global_pose/frame_positions");
  const auto velocities = testing::ReadNpyFloat64(testing::DataRoot() / kComma / "global_pose/frame_velocities");
  if (!times || !positions || !velocities) return std::nullopt;
  const Eigen::Vector3d p0(positions->at(0, 0), positions->at(0, 1), positions->at(0, 2));
  const double lon = std::atan2(p0.y(), p0.x());
  const double lat = std::atan2(p0.z(), p0.head<2>().norm());
  const Eigen::Vector3d east(-std::sin(lon), std::cos(lon), 0.0);
  const Eigen::Vector3d north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  Fused fused;
  for (std::size_t i = 0; i < times->rows(); ++i) {
    const Eigen::Vector3d v(velocities->at(i, 0), velocities->at(i, 1), velocities->at(i, 2));
    double course = std::atan2(v.dot(north), v.dot(east));
    if (!fused.course.empty()) {
      course = fused.course.back() + std::remainder(course - fused.course.back(), 2.0 * std::numbers::pi);
    }
    fused.t.push_back(times->at(i));
    fused.course.push_back(course);
    if (i > 0) {
      const Eigen::Vector3d a(positions->at(i - 1, 0), positions->at(i - 1, 1), positions->at(i - 1, 2));
      const Eigen::Vector3d b(positions->at(i, 0), positions->at(i, 1), positions->at(i, 2));
      fused.path_length += (b - a).norm();
    }
  }
  return fused;
}

// Heading of the dead-reckoned track at time t (linear between samples).
double HeadingAt(const std::vector<OdometrySample>& samples, double t_s) {
  const TimeNs t = static_cast<TimeNs>(t_s * 1e9);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].time_ns >= t) return samples[i].local_T_vehicle.theta();
  }
  return samples.back().local_T_vehicle.theta();
}

TEST(CanOdometryReal, Rav4WheelSpeedsEqualCommasDecode) {
  FLAT2D_REQUIRE_DATA(dbc, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log, kRav4Log);
  FLAT2D_REQUIRE_DATA(reference_path, std::string(kComma) + "processed_log/CAN/wheel_speed/value");
  const LogRun run = RunLog(dbc, log, LoadShipped("toyota_rav4_hybrid_2017.textproto"));
  const auto reference = testing::ReadNpyFloat64(reference_path);
  ASSERT_TRUE(reference.has_value());
  std::size_t sets = 0;
  double worst = 0.0;
  for (const auto& m : run.measurements) {
    if (!m.wheel_speeds) continue;
    ASSERT_LT(sets, reference->rows());
    const double ours[4] = {m.wheel_speeds->front_left_mps, m.wheel_speeds->front_right_mps,
                            m.wheel_speeds->rear_left_mps, m.wheel_speeds->rear_right_mps};
    for (std::size_t c = 0; c < 4; ++c) worst = std::max(worst, std::abs(ours[c] - reference->at(sets, c)));
    ++sets;
  }
  EXPECT_EQ(sets, reference->rows());  // 4974: every WHEEL_SPEEDS frame
  EXPECT_LT(worst, 1e-9) << "largest difference from comma's decode, m/s";
  EXPECT_EQ(run.decoder.checksum_failures, 0u);
  // SPEED's checksum is in the DBC; the shipped mapping adds KINEMATICS and STEER_ANGLE_SENSOR.
  EXPECT_EQ(run.decoder.checksum_checked, 4974u + 4974u + 2487u);
}

TEST(CanOdometryReal, Rav4PathLengthAndHeadingAgainstTheFusedTrajectory) {
  FLAT2D_REQUIRE_DATA(dbc, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log, kRav4Log);
  FLAT2D_REQUIRE_DATA(fused_dir, std::string(kComma) + "global_pose");
  const auto fused = LoadFused();
  ASSERT_TRUE(fused.has_value());
  const OdometryConfig shipped = LoadShipped("toyota_rav4_hybrid_2017.textproto");
  const LogRun run = RunLog(dbc, log, shipped);
  ASSERT_GT(run.samples.size(), 4000u);

  // Over the span both cover (the fused track starts 40 ms before the first CAN sample).
  const TimeNs from = std::max(run.samples.front().time_ns, static_cast<TimeNs>(fused->t.front() * 1e9));
  const TimeNs to = std::min(run.samples.back().time_ns, static_cast<TimeNs>(fused->t.back() * 1e9));
  double fused_length = 0.0;  // recompute over the same span
  {
    const auto positions = testing::ReadNpyFloat64(testing::DataRoot() / kComma / "global_pose/frame_positions");
    for (std::size_t i = 1; i < fused->t.size(); ++i) {
      if (fused->t[i - 1] * 1e9 < static_cast<double>(from) || fused->t[i] * 1e9 > static_cast<double>(to)) continue;
      fused_length += std::sqrt(std::pow(positions->at(i, 0) - positions->at(i - 1, 0), 2) +
                                std::pow(positions->at(i, 1) - positions->at(i - 1, 1), 2) +
                                std::pow(positions->at(i, 2) - positions->at(i - 1, 2), 2));
    }
  }
  const double ours = PathLength(run.samples, from, to);
  const double ratio = ours / fused_length;
  std::printf("RAV4: dead-reckoned %.2f m, fused %.2f m over %.2f s: ratio %.4f\n", ours, fused_length,
              static_cast<double>(to - from) * 1e-9, ratio);
  EXPECT_NEAR(ratio, 1.0, 0.02);

  // Heading: the yaw-rate sensor's mean minus the fused course rate is its bias.
  double yaw_sum = 0.0;
  int yaw_count = 0;
  for (const auto& m : run.measurements) {
    if (m.yaw_rate_radps) {
      yaw_sum += *m.yaw_rate_radps;
      ++yaw_count;
    }
  }
  const double duration = fused->t.back() - fused->t.front();
  const double course_rate = (fused->course.back() - fused->course.front()) / duration;
  const double bias = yaw_sum / yaw_count - course_rate;
  std::printf("RAV4: course change %.3f deg in %.2f s; yaw-rate sensor bias %.4f deg/s\n",
              (fused->course.back() - fused->course.front()) * kRadToDeg, duration, bias * kRadToDeg);
  EXPECT_NEAR(bias * kRadToDeg, -0.40, 0.05);

  // Drift of the dead-reckoned heading against the fused course, as shipped (the bias is
  // learnt only standing still, and this drive never stops) and with the bias removed.
  auto drift_of = [&](const LogRun& r) {
    const double t0 = std::max(fused->t.front(), static_cast<double>(r.samples.front().time_ns) * 1e-9);
    double worst = 0.0, end = 0.0;
    const double theta0 = HeadingAt(r.samples, t0);
    for (std::size_t i = 0; i < fused->t.size(); ++i) {
      if (fused->t[i] < t0) continue;
      end = (HeadingAt(r.samples, fused->t[i]) - theta0) - (fused->course[i] - fused->course.front());
      worst = std::max(worst, std::abs(end));
    }
    return std::pair(end, worst);
  };
  const auto [raw_end, raw_worst] = drift_of(run);
  OdometryConfig corrected = shipped;
  corrected.mutable_dead_reckoning()->set_yaw_rate_bias_radps(bias);
  const auto [corrected_end, corrected_worst] = drift_of(RunLog(dbc, log, corrected));
  OdometryConfig wheels = shipped;
  wheels.mutable_dead_reckoning()->set_heading_from_wheels(true);
  const auto [wheels_end, wheels_worst] = drift_of(RunLog(dbc, log, wheels));
  std::printf("RAV4 heading drift over 60 s (deg): shipped %.2f (worst %.2f); bias removed %.2f "
              "(worst %.2f); from wheels %.2f (worst %.2f)\n",
              raw_end * kRadToDeg, raw_worst * kRadToDeg, corrected_end * kRadToDeg,
              corrected_worst * kRadToDeg, wheels_end * kRadToDeg, wheels_worst * kRadToDeg);
  EXPECT_NEAR(raw_end, bias * duration, 0.02);  // the drift is the bias, nothing else
  EXPECT_LT(std::abs(corrected_end) * kRadToDeg, 1.0);
}

// Per-second means of what the bus says, for comparisons that single frames are too
// quantised for (a 0.01 km/h step is 0.002 rad/s of wheel yaw rate).
struct SecondMeans {
  double rear_left = 0, rear_right = 0, sensor_yaw = 0;
  int wheel_count = 0, yaw_count = 0;
};

TEST(CanOdometryReal, Rav4SignalsArePhysicallyConsistent) {
  FLAT2D_REQUIRE_DATA(dbc, kRav4Dbc);
  FLAT2D_REQUIRE_DATA(log, kRav4Log);
  const OdometryConfig config = LoadShipped("toyota_rav4_hybrid_2017.textproto");
  const double track = config.dead_reckoning().track_m();
  const LogRun run = RunLog(dbc, log, config);
  ASSERT_FALSE(run.measurements.empty());
  const double t0 = static_cast<double>(run.measurements.front().time_ns) * 1e-9;
  std::vector<SecondMeans> seconds(61);
  double speed_integral = 0.0, rear_integral = 0.0;
  double previous_speed_t = -1.0, previous_speed = 0.0, previous_rear_t = -1.0, previous_rear = 0.0;
  for (const auto& m : run.measurements) {
    const double t = static_cast<double>(m.time_ns) * 1e-9;
    SecondMeans& second = seconds[std::min<std::size_t>(60, static_cast<std::size_t>(t - t0))];
    if (m.yaw_rate_radps) second.sensor_yaw += *m.yaw_rate_radps, ++second.yaw_count;
    if (m.vehicle_speed_mps) {
      EXPECT_GE(*m.vehicle_speed_mps, 0.0);
      EXPECT_LE(*m.vehicle_speed_mps, 50.0);
      if (previous_speed_t >= 0.0) speed_integral += previous_speed * (t - previous_speed_t);
      previous_speed_t = t;
      previous_speed = *m.vehicle_speed_mps;
    }
    if (!m.wheel_speeds) continue;
    const auto& w = *m.wheel_speeds;
    for (double v : {w.front_left_mps, w.front_right_mps, w.rear_left_mps, w.rear_right_mps}) {
      EXPECT_GE(v, 0.0);  // driving forward all along
      EXPECT_LE(v, 50.0);
    }
    const double rear = 0.5 * (w.rear_left_mps + w.rear_right_mps);
    if (previous_rear_t >= 0.0) rear_integral += 0.5 * (previous_rear + rear) * (t - previous_rear_t);
    previous_rear_t = t;
    previous_rear = rear;
    second.rear_left += w.rear_left_mps, second.rear_right += w.rear_right_mps, ++second.wheel_count;
  }

  // Per second: left and right agree within a few percent when the sensor says straight
  // (within 0.1 deg/s of its -0.40 deg/s bias); sensor and wheel-speed difference agree in
  // sign and magnitude (slope of sensor on wheels, means removed: they carry the biases).
  double worst_straight = 0.0, mx = 0, my = 0;
  std::vector<std::pair<double, double>> pairs;
  for (const SecondMeans& s : seconds) {
    if (s.wheel_count == 0 || s.yaw_count == 0) continue;
    const double left = s.rear_left / s.wheel_count, right = s.rear_right / s.wheel_count;
    const double sensor = s.sensor_yaw / s.yaw_count;
    if (std::abs(sensor * kRadToDeg + 0.40) < 0.1) {
      worst_straight = std::max(worst_straight, std::abs(left - right) / (0.5 * (left + right)));
    }
    pairs.emplace_back((right - left) / track, sensor);
    mx += pairs.back().first, my += pairs.back().second;
  }
  mx /= static_cast<double>(pairs.size()), my /= static_cast<double>(pairs.size());
  double sxy = 0, sxx = 0, syy = 0;
  for (auto [x, y] : pairs) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx), syy += (y - my) * (y - my);
  const double correlation = sxy / std::sqrt(sxx * syy), slope = sxy / sxx;
  std::printf("RAV4 per second: rear L/R differ by at most %.2f %% going straight; sensor on wheel yaw "
              "rate: correlation %.3f, slope %.3f, wheel-yaw offset %.3f deg/s\n",
              100.0 * worst_straight, correlation, slope, (mx)*kRadToDeg);
  EXPECT_LT(worst_straight, 0.03);
  EXPECT_GT(correlation, 0.7);
  EXPECT_NEAR(slope, 1.0, 0.35);

  // The dead-reckoned distance is the integral of the speed it used (rear wheels), and the
  // SPEED message (the speedometer) reads a little higher, as speedometers are made to.
  const double distance = PathLength(run.samples, run.samples.front().time_ns, run.samples.back().time_ns);
  std::printf("RAV4: dead-reckoned %.2f m, rear-wheel speed integral %.2f m, SPEED integral %.2f m "
              "(+%.2f %%)\n", distance, rear_integral, speed_integral,
              100.0 * (speed_integral / rear_integral - 1.0));
  EXPECT_NEAR(distance / rear_integral, 1.0, 0.001);
  EXPECT_GT(speed_integral / rear_integral, 1.0);
  EXPECT_LT(speed_integral / rear_integral, 1.04);
}

}  // namespace
}  // namespace flat2d::localization
