// One range measurement made ready for registration: the file read, the sensor's
// projection chosen, the points' surface statistics computed (thesis 5.1.1).
//
// Sensors: a pinhole depth camera (TUM depth PNG); spinning LiDARs whose rows are the
// lasers of a Velodyne laser table (VLP-16, HDL-32E, VLP-32C, recognised from the points'
// elevations when not given); KITTI's HDL-64E binned into equal elevation rows; and
// unorganized clouds (PLY scans, anything else), whose statistics come from a KD-tree
// and which register in KD-tree mode.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"
#include "hal/velodyne/model.hpp"
#include "maps/range3d/index_image.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::range3d {

enum class SensorModel { kAuto, kPinhole, kVlp16, kHdl32e, kVlp32c, kKitti64, kUnorganized };

std::string_view SensorModelName(SensorModel sensor);
std::optional<SensorModel> ParseSensorModel(std::string_view name);

struct RangeFrameOptions {
  SensorModel sensor = SensorModel::kAuto;
  // TUM's recipe for its depth images (fr1 depth is registered to the colour camera).
  PinholeIntrinsics intrinsics{640, 480, 525.0F, 525.0F, 319.5F, 239.5F};
  double depth_scale = 5000.0;   // TUM depth PNG: metres = value / 5000
  float max_depth_m = 8.0F;      // Kinect v1 depth beyond ~8 m is noise
  // Depth images: every image_scale-th pixel of every image_scale-th row (fx, cx scaled
  // to match); 2 makes a 640x480 frame 320x240, a quarter of the work.
  int image_scale = 1;
  int lidar_columns = 2160;      // ~0.167 deg: a 10 Hz HDL-32E's firing spacing
  // Statistics: R = 0.1 m for depth cameras (5.1.1); LiDAR rows are 1-2 deg apart, so a
  // neighbourhood of 0.1 m holds a single ring beyond ~3 m: 0.3 m there (the HDL-32E
  // pair lands 0.3 cm nearer both references with 0.3 than with 0.5 or 0.2).
  SurfaceStatisticsOptions depth_statistics{};
  SurfaceStatisticsOptions lidar_statistics{0.3F, 6, 32, 0.1F, 0.02F, 1e-3F};
  // Unorganized: R in the cloud's units, and where the scanner was.
  SurfaceStatisticsOptions unorganized_statistics{0.1F, 8, 32, 0.1F, 0.02F, 1e-3F};
  Eigen::Vector3f viewpoint = Eigen::Vector3f::Zero();
};

struct RangeFrame {
  SensorModel sensor = SensorModel::kUnorganized;
  RangeProjection projection;  // rows() == 0 for unorganized clouds
  SurfelCloud cloud;
  IndexImage image;            // organized: which point each pixel of `projection` shows
  float statistics_radius_m = 0.1F;  // the R the normals were fitted over

  bool organized() const { return projection.rows() > 0; }
};

// Reads a .png (TUM depth), .pcd, .ply or .bin (KITTI) file and prepares it.
Result<RangeFrame> LoadRangeFrame(const std::filesystem::path& path, const RangeFrameOptions& options);

RangeFrame FrameFromDepth(const hal::cloud::DepthImage& depth, const RangeFrameOptions& options);
// The points of every scale-th pixel and row of `depth` (intrinsics scaled to match) and
// their index image, statistics not yet computed (SNICP's pyramid levels).
RangeFrame UnprojectDepth(const hal::cloud::DepthImage& depth, const RangeFrameOptions& options, int scale);
// The frame's statistics fitted again over radius R (points, projection and index image
// unchanged), with the options of its sensor from `options`: the later radii of a
// coarse-to-fine registration (RegisterFramesOverRadii).
void RefitStatistics(const RangeFrameOptions& options, float radius_m, RangeFrame& frame);

// `sensor` kAuto: a Velodyne model whose laser elevations the points match, else unorganized.
RangeFrame FrameFromCloud(const hal::cloud::PointCloud& cloud, SensorModel sensor, const RangeFrameOptions& options);

// The Velodyne model (kVlp16, kHdl32e, kVlp32c) whose laser elevations 95 % of the
// points lie within 0.1 deg of, or kUnorganized.
SensorModel DetectLidar(const std::vector<Eigen::Vector3f>& points);

// The range-frame model of a decoded Velodyne model.
SensorModel SensorModelOf(hal::velodyne::Model model);

// The spherical projection of an organized LiDAR model with `columns` columns. With a
// rotation speed (rpm > 0), a Velodyne's columns follow its firing sequences rather than
// azimuth alone: every laser of one sequence lands in one column (the VLP-16's 16 lasers
// span 0.75 of a 2160-column image's column at 600 rpm). Vertical stacks then share a column,
// which Algorithm 7 needs (maps/features3d/vertical_removal.hpp). Registration keeps 0.
RangeProjection LidarProjection(SensorModel sensor, int columns, double rotation_rpm = 0.0);

}  // namespace flat2d::maps::range3d
