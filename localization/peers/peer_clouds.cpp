// Reading and filtering the peers' input clouds (peer_clouds.hpp).
#include "localization/peers/peer_clouds.hpp"

#include <cmath>
#include <string>

#include "hal/cloud/kitti_bin_file.hpp"
#include "hal/cloud/pcd_file.hpp"
#include "hal/cloud/ply_file.hpp"
#include "hal/cloud/tum_depth_png.hpp"

namespace flat2d::localization::peers {
namespace {

Result<Points> NonEmpty(Points points, const std::filesystem::path& path) {
  if (points.empty()) return MakeError(path.string() + ": no measured point");
  return points;
}

Result<Points> FromCloud(Result<hal::cloud::PointCloud> cloud, const std::filesystem::path& path) {
  if (!cloud.ok()) return cloud.error();
  return NonEmpty(MeasuredPoints(*cloud), path);
}

}  // namespace

Result<Points> LoadPeerPoints(const std::filesystem::path& path, const PeerCloudOptions& options) {
  const std::string extension = path.extension().string();
  if (extension == ".pcd") return FromCloud(hal::cloud::ReadPcd(path), path);
  if (extension == ".ply") return FromCloud(hal::cloud::ReadPly(path), path);
  if (extension == ".bin") return FromCloud(hal::cloud::ReadKittiBin(path), path);
  if (extension == ".png") {
    auto image = hal::cloud::ReadTumDepthPng(path);
    if (!image.ok()) return image.error();
    return NonEmpty(UnprojectDepth(*image, options.intrinsics, options.max_depth_m), path);
  }
  return MakeError(path.string() + ": unknown file type (.pcd, .ply, .bin or .png)");
}

Points MeasuredPoints(const hal::cloud::PointCloud& cloud) {
  Points points;
  points.reserve(cloud.points.size());
  for (const Eigen::Vector3f& p : cloud.points) {
    if (p.allFinite() && !p.isZero(0.0f)) points.push_back(p);
  }
  return points;
}

Points UnprojectDepth(const hal::cloud::DepthImage& image, const PinholeIntrinsics& intrinsics, double max_depth_m) {
  Points points;
  points.reserve(image.depth_m.size());
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const double z = image.at(row, col);
      if (!(z > 0.0 && z <= max_depth_m)) continue;
      points.emplace_back(static_cast<float>((col - intrinsics.cx) * z / intrinsics.fx),
                          static_cast<float>((row - intrinsics.cy) * z / intrinsics.fy), static_cast<float>(z));
    }
  }
  return points;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr ToPcl(const Points& points) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(points.size());
  for (const Eigen::Vector3f& p : points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  cloud->is_dense = true;  // MeasuredPoints and UnprojectDepth keep finite points only
  return cloud;
}

std::shared_ptr<open3d::geometry::PointCloud> ToOpen3d(const Points& points) {
  auto cloud = std::make_shared<open3d::geometry::PointCloud>();
  cloud->points_.reserve(points.size());
  for (const Eigen::Vector3f& p : points) cloud->points_.push_back(p.cast<double>());
  return cloud;
}

}  // namespace flat2d::localization::peers
