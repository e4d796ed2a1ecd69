// One Velodyne revolution as a 3D point cloud for registration (thesis 5.1): every return of
// its fans in the sensor frame of the revolution's first fan.
//
// A revolution takes 0.1 s at 10 Hz, in which a car at 9 m/s moves 0.9 m: the fans are
// measured from different places. Given the sensor's motion since the first fan
// (reference_T_sensor at each fan's time, from odometry or a constant velocity), each fan's
// points are moved into the reference frame ("deskewing", the same compensation the
// revolution gridder applies in the plane). Only the returns of the first fan's kind are
// kept, so a dual-return capture gives one point per laser and firing.
#pragma once

#include <functional>
#include <optional>

#include <Eigen/Geometry>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/time.hpp"
#include "hal/velodyne/revolution.hpp"
#include "maps/grid/interpolated_poses.hpp"

namespace flat2d::localization::tools {

// reference_T_sensor(t): the sensor at time t seen from the sensor at the reference time.
using SensorMotion = std::function<Eigen::Isometry3d(TimeNs)>;

// The sensor's motion from t0 to t by dead-reckoned vehicle poses (in the plane, lifted):
// sensor(t0)_T_sensor(t); nullopt where the odometry does not cover both times.
std::optional<Eigen::Isometry3d> OdometrySensorMotion(const maps::InterpolatedPoses& odometry,
                                                      const Eigen::Isometry3d& vehicle_T_sensor, TimeNs t0, TimeNs t);

// `motion` empty: the sensor is taken as standing still over the revolution.
hal::cloud::PointCloud RevolutionCloud(const hal::velodyne::Revolution& revolution, const SensorMotion& motion);

// The pose a fraction `f` of the way along `motion` (f in [0, 1], or a little beyond):
// the rotation's angle scaled about its axis, the translation scaled (small motions).
Eigen::Isometry3d ScaledMotion(const Eigen::Isometry3d& motion, double f);

}  // namespace flat2d::localization::tools
