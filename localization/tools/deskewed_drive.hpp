// A Velodyne drive walked revolution by revolution over CAN odometry, each revolution one
// deskewed 3D cloud at a dead-reckoned pose: the front half of the 3D landmark SLAM pipeline
// (thesis 8.2), shared by `flat2d-map build --mode landmarks` and the peers fed the same
// revolutions (flat2d-peer-narf-slam), so that they differ in what they extract alone.
//
// Steps: (1) the CAN log dead-reckoned into planar poses (odometry_poses.hpp); (2) the
// capture's datagrams assembled into revolutions; (3) each complete revolution that the
// odometry covers deskewed by it into the sensor frame of its first fan
// (revolution_cloud.hpp); (4) its vehicle pose at the first fan's stamp, lifted to SE(3) and
// placed so that the first one is the anchor track's pose there (else the odometry's own),
// handed with the cloud to the caller.
#pragma once

#include <filesystem>
#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/evaluation/relations.hpp"

namespace flat2d::localization::tools {

struct DeskewedDriveOptions {
  std::filesystem::path capture;
  std::filesystem::path can_log, dbc, odometry_config;  // CAN odometry: required
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();  // the sensor's mounting
  hal::velodyne::VelodyneStreamOptions stream;
  // The first revolution's vehicle pose (a truth or GNSS track); empty: the odometry's.
  std::vector<evaluation::TimedPose> anchor;
  int max_revolutions = 0;  // 0: every complete revolution
};

// One revolution as the caller sees it; valid during the call only.
struct DeskewedRevolution {
  TimeNs stamp = 0;  // of the first fan
  const hal::cloud::PointCloud& cloud;  // in the sensor frame of the first fan
  Eigen::Isometry3d world_T_vehicle = Eigen::Isometry3d::Identity();  // odometry, anchored
  hal::velodyne::Model model;
  double deskew_ms = 0.0;  // building `cloud`
};

struct DeskewedDriveSummary {
  int complete_revolutions = 0;          // in the capture (up to max_revolutions)
  int revolutions = 0;                   // handed to the caller
  int revolutions_without_odometry = 0;  // outside the CAN log's time: skipped
};

using RevolutionHandler = std::function<void(const DeskewedRevolution&)>;

// Calls `handle` once per revolution in capture order. Errors name the file: the capture,
// CAN log, DBC or odometry configuration unreadable, an unsupported model, no complete
// revolution, or none that the odometry covers.
Result<DeskewedDriveSummary> WalkDeskewedDrive(const DeskewedDriveOptions& options, const RevolutionHandler& handle);

}  // namespace flat2d::localization::tools
