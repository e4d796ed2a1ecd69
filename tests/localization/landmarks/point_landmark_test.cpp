// Point landmarks (key-points, thesis 8.2) in the landmark SLAM back end: the point factor's
// Jacobians (F4', point_factor.hpp) against central differences, the distance gate of
// association, and a loop seen through key-points alone (no planes or lines) on which the
// graph must beat the drifting dead reckoning it starts from. The drive's truth and
// odometry come from synthetic_landmark_drive.hpp; the key-points are drawn here.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "localization/landmarks/landmark_association.hpp"
#include "localization/landmarks/landmark_slam.hpp"
#include "localization/landmarks/point_factor.hpp"
#include "tests/localization/landmarks/random_geometry.hpp"
#include "tests/localization/landmarks/synthetic_landmark_drive.hpp"

namespace flat2d::localization::landmarks {
namespace {

using testing::CentralDifference;
using testing::JacobiansAgree;
using testing::RandomPose;
using testing::RandomVector;

TEST(PointFactor, JacobiansMatchCentralDifferences) {
  const unsigned seed = 3501;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < 50; ++i) {
    // Far poses (1 km) with the point near them, as anchoring keeps it; and the inverse
    // case of a point far from a pose near the origin.
    const bool far_pose = i % 3 == 0;
    const Eigen::Isometry3d anchor_T_sensor = RandomPose(rng, far_pose ? 1e3 : 5.0);
    const Eigen::Vector3d near = far_pose ? Eigen::Vector3d(anchor_T_sensor.translation()) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d point = near + RandomVector(rng, far_pose ? 20.0 : 200.0);
    const Eigen::Vector3d measured = anchor_T_sensor.inverse() * point + RandomVector(rng, i % 2 == 0 ? 0.0 : 0.3);
    const PointFactorLinearization lin = LinearizePoint(anchor_T_sensor, point, measured);
    EXPECT_LE((lin.error - PointError(anchor_T_sensor, point, measured)).norm(), 1e-9) << "case " << i;
    if (i % 2 == 0) {
      EXPECT_LE(lin.error.norm(), 1e-9) << "case " << i;  // measured where predicted
    }
    const auto numeric_pose = CentralDifference<3, 6>(
        [&](const Vector6d& d) { return PointError(RetractPose(anchor_T_sensor, d), point, measured); }, 1e-6);
    const auto numeric_point = CentralDifference<3, 3>(
        [&](const Eigen::Vector3d& d) { return PointError(anchor_T_sensor, Eigen::Vector3d(point + d), measured); }, 1e-6);
    EXPECT_TRUE(JacobiansAgree(lin.jacobian_pose, numeric_pose, 1e-5)) << "case " << i << "\n" << lin.jacobian_pose << "\n\n" << numeric_pose;
    EXPECT_TRUE(JacobiansAgree(lin.jacobian_point, numeric_point, 1e-6)) << "case " << i;
  }
}

TEST(PointFactor, VehiclePoseJacobianMatchesCentralDifferences) {
  const unsigned seed = 3502;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < 50; ++i) {
    ObservationGeometry g;
    g.world_T_vehicle = RandomPose(rng, i % 3 == 0 ? 1e3 : 100.0);
    g.vehicle_T_sensor = RandomPose(rng, 2.0);
    g.world_T_anchor.translation() = g.world_T_vehicle.translation() + RandomVector(rng, 10.0);
    g.sensor_of_vehicle = SensorPerturbationOfVehicle(g.vehicle_T_sensor);
    const Eigen::Vector3d point = RandomVector(rng, 30.0);  // in the anchor frame
    const Eigen::Vector3d measured = RandomVector(rng, 30.0);
    const PointFactorLinearization lin = LinearizePointObservation(g, point, measured);
    const auto numeric = CentralDifference<3, 6>(
        [&](const Vector6d& d) {
          ObservationGeometry moved = g;
          moved.world_T_vehicle = RetractPose(g.world_T_vehicle, d);
          return PointError(moved.AnchorTSensor(), point, measured);
        },
        1e-6);
    EXPECT_TRUE(JacobiansAgree(lin.jacobian_pose, numeric, 1e-5)) << "case " << i;
  }
}

TEST(PointAssociation, NearestWithinTheGateWins) {
  const AssociationGates gates;  // point_distance_m 0.5
  const std::vector<Eigen::Vector3d> landmarks = {{0.0, 0.0, 0.0}, {0.6, 0.0, 0.0}, {10.0, 0.0, 0.0}};
  EXPECT_EQ(AssociatePoint(landmarks, Eigen::Vector3d(0.2, 0.0, 0.0), gates), 0);
  EXPECT_EQ(AssociatePoint(landmarks, Eigen::Vector3d(0.4, 0.0, 0.0), gates), 1);  // both within 0.5 m: the nearer
  EXPECT_EQ(AssociatePoint(landmarks, Eigen::Vector3d(10.0, 0.0, 0.45), gates), 2);
  EXPECT_FALSE(AssociatePoint(landmarks, Eigen::Vector3d(5.0, 0.0, 0.0), gates).has_value());
  EXPECT_FALSE(AssociatePoint({}, Eigen::Vector3d::Zero(), gates).has_value());
}

// Key-points scattered around the 8 m loop, 3-25 m from its centre and 0-4 m high, at
// least 1.5 m apart (a NARF support apart, and more than twice the gate).
std::vector<Eigen::Vector3d> KeypointWorld(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < count) {
    const double radius = unit(rng) < 0.3 ? 3.0 + 3.0 * unit(rng) : 11.0 + 14.0 * unit(rng);
    const double phi = 2.0 * std::numbers::pi * unit(rng);
    const Eigen::Vector3d p(radius * std::cos(phi), radius * std::sin(phi), 4.0 * unit(rng));
    bool crowded = false;
    for (const Eigen::Vector3d& q : points) crowded = crowded || (p - q).norm() < 1.5;
    if (!crowded) points.push_back(p);
  }
  return points;
}

struct PointRun {
  double slam_rmse_m = 0.0;
  double odometry_rmse_m = 0.0;
  LandmarkSlamStats stats;
  std::vector<LandmarkSlam::PointLandmark> points;
};

// Each revolution sees the points within 20 m with 3 cm noise per axis and one clutter
// key-point; the graph gets no plane or line.
PointRun RunPointSlam(const testing::Drive& drive, const std::vector<Eigen::Vector3d>& world, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.03);
  LandmarkSlam slam(LandmarkSlamOptions{}, drive.vehicle_T_sensor);
  const maps::features3d::FeatureSet no_features;
  for (std::size_t k = 0; k < drive.revolutions.size(); ++k) {
    const testing::Revolution& r = drive.revolutions[k];
    const Eigen::Isometry3d sensor_T_world = (r.truth_world_T_vehicle * drive.vehicle_T_sensor).inverse();
    std::vector<Eigen::Vector3d> keypoints;
    for (const Eigen::Vector3d& p : world) {
      const Eigen::Vector3d seen = sensor_T_world * p;
      // Braces: the draws are made in order (a call's arguments have none).
      if (seen.norm() <= 20.0) keypoints.push_back(seen + Eigen::Vector3d{noise(rng), noise(rng), noise(rng)});
    }
    keypoints.push_back(RandomVector(rng, 15.0));
    slam.Add(static_cast<TimeNs>(k) * 100 * kNsPerMs, r.odometry_world_T_vehicle, no_features, keypoints);
  }
  slam.Finish();
  PointRun run;
  const std::vector<hal::trajectory::StampedPose> trajectory = slam.Trajectory();
  double slam_sum = 0.0, odometry_sum = 0.0;
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    const Eigen::Vector3d truth = drive.revolutions[k].truth_world_T_vehicle.translation();
    slam_sum += (trajectory[k].world_T_body.translation() - truth).squaredNorm();
    odometry_sum += (drive.revolutions[k].odometry_world_T_vehicle.translation() - truth).squaredNorm();
  }
  run.slam_rmse_m = std::sqrt(slam_sum / static_cast<double>(trajectory.size()));
  run.odometry_rmse_m = std::sqrt(odometry_sum / static_cast<double>(trajectory.size()));
  run.stats = slam.stats();
  run.points = slam.Points();
  std::printf("rmse slam %.3f m, odometry %.3f m; nodes %d, point landmarks %d, point factors %d, associated %d, "
              "downweighted %d, back end %.2f ms/revolution\n",
              run.slam_rmse_m, run.odometry_rmse_m, run.stats.pose_nodes, run.stats.point_landmarks,
              run.stats.point_factors, run.stats.associations, run.stats.downweighted_factors,
              run.stats.backend_ms_total / run.stats.revolutions);
  return run;
}

TEST(LandmarkSlam, LoopWithPointLandmarksOnlyBeatsDriftingOdometry) {
  const unsigned seed = 3503;
  std::printf("seed %u\n", seed);
  std::mt19937 world_rng(seed), noise_rng(seed + 1), corruption_rng(seed + 2), keypoint_rng(seed + 3);
  testing::DriveSettings settings;
  settings.features = false;  // truth and odometry only: the key-points are drawn here
  const testing::Drive drive = MakeDrive(testing::MakeLoopWorld(world_rng), settings, noise_rng, corruption_rng);
  const std::vector<Eigen::Vector3d> world = KeypointWorld(keypoint_rng, 60);
  const PointRun run = RunPointSlam(drive, world, keypoint_rng);
  EXPECT_GE(run.odometry_rmse_m, 0.5) << "the drive must drift for the test to mean anything";
  EXPECT_LE(run.slam_rmse_m * 3.0, run.odometry_rmse_m);
  EXPECT_LE(run.slam_rmse_m, 0.1);
  EXPECT_EQ(run.stats.plane_factors + run.stats.line_factors, 0);
  // Every true point seen often is one landmark within 10 cm; clutter makes landmarks seen once.
  int recovered = 0;
  for (const Eigen::Vector3d& p : world) {
    int near = 0;
    for (const LandmarkSlam::PointLandmark& l : run.points) near += l.observations >= 10 && (l.position - p).norm() <= 0.1;
    recovered += near == 1;
  }
  EXPECT_GE(recovered, 50) << "of " << world.size();
}

}  // namespace
}  // namespace flat2d::localization::landmarks
