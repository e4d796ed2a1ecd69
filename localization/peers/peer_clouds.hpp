// The clouds the registration peers are given: a range file read with flat2d's own readers
// (hal/cloud, the ones flat2d-map register uses), reduced to the points that are
// measurements, and those points as PCL and Open3D hold them.
//
// Steps: read by extension (.pcd, .ply, .bin KITTI, .png TUM depth); unproject a depth
// image with the pinhole model (x = (u - cx) z / fx, y = (v - cy) z / fy), dropping depth 0
// (no return) and depths beyond max_depth_m (the Kinect's depth noise grows with z^2);
// drop NaN points (organized clouds' holes) and points exactly at the origin (the HDL-32E's
// zero-range returns, 5032 of 69088 in the fast_gicp pair), which both libraries would
// otherwise match as surface points.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <open3d/geometry/PointCloud.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"

namespace flat2d::localization::peers {

// Sensor frame, metres.
using Points = std::vector<Eigen::Vector3f>;

// TUM RGB-D's default calibration, as flat2d-map register assumes.
struct PinholeIntrinsics {
  double fx = 525.0;
  double fy = 525.0;
  double cx = 319.5;
  double cy = 239.5;
};

struct PeerCloudOptions {
  PinholeIntrinsics intrinsics;  // depth images only
  double max_depth_m = 8.0;      // depth images only; deeper pixels are dropped
};

// The measured points of a range file; an error names the file (unreadable, unknown
// extension, no point left).
Result<Points> LoadPeerPoints(const std::filesystem::path& path, const PeerCloudOptions& options);

// The finite, non-zero points of `cloud`.
Points MeasuredPoints(const hal::cloud::PointCloud& cloud);

// The pixels of `image` with a depth in (0, max_depth_m], in the camera frame.
Points UnprojectDepth(const hal::cloud::DepthImage& image, const PinholeIntrinsics& intrinsics, double max_depth_m);

pcl::PointCloud<pcl::PointXYZ>::Ptr ToPcl(const Points& points);
std::shared_ptr<open3d::geometry::PointCloud> ToOpen3d(const Points& points);

}  // namespace flat2d::localization::peers
