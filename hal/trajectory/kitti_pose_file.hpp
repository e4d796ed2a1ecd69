// KITTI odometry ground truth (Geiger et al. 2012, devkit readme): poses/NN.txt, one line a
// frame, the 12 numbers of the top 3x4 of world_T_cam0(i), row-major, the world being the
// first frame's left camera (x right, y down, z forward).
//
// Every line must hold a rotation and a translation (ParseTransform's checks); a bad line
// is an error naming the file and line, an empty file is an error.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"

namespace flat2d::hal::trajectory {

Result<std::vector<Eigen::Isometry3d>> ReadKittiPoses(const std::filesystem::path& path);
Result<std::vector<Eigen::Isometry3d>> ParseKittiPoses(std::string_view text, std::string_view source_name);

// The camera frame as a vehicle frame (x forward, y left, z up): KITTI's poses turned into
// world_T_vehicle with the world z up, for tools that think in headings.
Eigen::Isometry3d VehicleFromKittiCamera(const Eigen::Isometry3d& world_T_cam0);

// calib.txt's "Tr:" line: cam0_T_velo, the Velodyne in the left camera's frame. A file
// without it, or with a bad one, is an error naming the file (and line).
Result<Eigen::Isometry3d> ReadKittiCalibration(const std::filesystem::path& path);
Result<Eigen::Isometry3d> ParseKittiCalibration(std::string_view text, std::string_view source_name);

// KITTI's camera poses as the Velodyne's, world_T_velo(i) = Tr^-1 P_0^-1 P_i Tr: the world
// becomes the first scan's Velodyne frame (x forward, y left, z up).
std::vector<Eigen::Isometry3d> VelodyneFromKittiCamera(const std::vector<Eigen::Isometry3d>& world_T_cam0,
                                                       const Eigen::Isometry3d& cam0_T_velo);

}  // namespace flat2d::hal::trajectory
