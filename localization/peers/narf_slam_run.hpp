// The NARF peer of landmark SLAM (thesis 8.2, Fig. 8.5-8.6): the pipeline of `flat2d-map
// build --mode landmarks` with NARF key-points in place of lines and planes. The same
// capture walk (deskewed_drive.hpp: every revolution deskewed by the CAN odometry, its pose
// dead-reckoned and anchored), the same back end with the same options
// (localization/landmarks/landmark_slam.hpp, point landmarks: point_factor.hpp); only what
// each revolution hands the graph differs: the key-points of narf_keypoints.hpp, in the
// sensor frame of the revolution's first fan.
#pragma once

#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/landmarks/landmark_slam.hpp"
#include "localization/peers/narf_keypoints.hpp"
#include "localization/tools/deskewed_drive.hpp"

namespace flat2d::localization::peers {

struct NarfSlamOptions {
  tools::DeskewedDriveOptions drive;  // capture, CAN odometry, mounting, anchor, max revolutions
  NarfOptions narf;
  landmarks::LandmarkSlamOptions slam;  // as build --mode landmarks: the defaults
};

struct NarfSlamResult {
  std::vector<hal::trajectory::StampedPose> trajectory;  // world_T_vehicle per revolution
  std::vector<hal::trajectory::StampedPose> odometry;    // the CAN odometry from the same first pose
  std::vector<landmarks::LandmarkSlam::PointLandmark> points;
  landmarks::LandmarkSlamStats stats;
  int revolutions = 0;
  int revolutions_without_odometry = 0;
  int image_width = 0;  // of the range images (the first revolution's)
  int image_height = 0;
  std::vector<int> keypoints;        // per revolution
  std::vector<double> deskew_ms;     // per revolution: the deskewed cloud
  std::vector<double> keypoints_ms;  // per revolution: range image, borders, NARF
  std::vector<double> keypoints_cpu_ms;  // the same in process CPU time (one thread: unlike the
                                         // wall time, not inflated by a loaded machine)
  std::vector<double> slam_ms;       // per revolution: the graph's share
  double finish_ms = 0.0;            // the final optimization
};

// Errors as WalkDeskewedDrive's.
Result<NarfSlamResult> RunNarfSlam(const NarfSlamOptions& options);

}  // namespace flat2d::localization::peers
