#include "maps/range3d/range_frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "hal/cloud/kitti_bin_file.hpp"
#include "hal/cloud/pcd_file.hpp"
#include "hal/cloud/ply_file.hpp"
#include "hal/cloud/tum_depth_png.hpp"
#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/laser_table.hpp"
#include "maps/range3d/depth_cloud.hpp"
#include "maps/range3d/neighbour_statistics.hpp"

namespace flat2d::maps::range3d {

namespace {

constexpr float kDegToRad = 3.14159265358979F / 180.0F;

struct SensorName {
  SensorModel sensor;
  std::string_view name;
};
constexpr std::array<SensorName, 7> kSensorNames{{{SensorModel::kAuto, "auto"},
                                                  {SensorModel::kPinhole, "pinhole"},
                                                  {SensorModel::kVlp16, "vlp16"},
                                                  {SensorModel::kHdl32e, "hdl32e"},
                                                  {SensorModel::kVlp32c, "vlp32c"},
                                                  {SensorModel::kKitti64, "kitti64"},
                                                  {SensorModel::kUnorganized, "unorganized"}}};

hal::velodyne::Model VelodyneModelOf(SensorModel sensor) {
  switch (sensor) {
    case SensorModel::kVlp16: return hal::velodyne::Model::kVlp16;
    case SensorModel::kVlp32c: return hal::velodyne::Model::kVlp32c;
    default: return hal::velodyne::Model::kHdl32e;
  }
}

// The laser elevations of a model, highest first (the rows of its range image).
std::vector<float> RowElevations(SensorModel sensor) {
  const hal::velodyne::LaserTable table = hal::velodyne::DefaultLaserTable(VelodyneModelOf(sensor));
  std::vector<float> elevation;
  for (int laser = 0; laser < table.num_lasers; ++laser) {
    elevation.push_back(static_cast<float>(table.lasers[static_cast<std::size_t>(laser)].elevation_rad));
  }
  std::sort(elevation.rbegin(), elevation.rend());
  elevation.erase(std::unique(elevation.begin(), elevation.end()), elevation.end());
  return elevation;
}

// Per row, the columns the sensor turns between the first firing of a sequence and the
// row's laser firing, at `rotation_rpm` (empty where the shift does not apply). The sensor
// turns clockwise seen from above, the image's azimuth grows counter-clockwise, so a later
// laser's point lies that many columns before the sequence's first: added back, the whole
// sequence shares a column. Not for lasers with azimuth offsets (the VLP-32C's up to 4 deg):
// one sequence spans many columns there, and a pole's points stay together only by azimuth.
std::vector<float> FiringColumnShifts(SensorModel sensor, int columns, double rotation_rpm) {
  if (rotation_rpm <= 0.0 || sensor == SensorModel::kKitti64) return {};
  const hal::velodyne::Model model = VelodyneModelOf(sensor);
  const hal::velodyne::LaserTable table = hal::velodyne::DefaultLaserTable(model);
  const hal::velodyne::FiringTiming timing = hal::velodyne::TimingFor(model);
  const std::vector<float> rows = RowElevations(sensor);
  if (static_cast<int>(rows.size()) != table.num_lasers) return {};  // two lasers share a row
  const double columns_per_us = rotation_rpm / 60.0 * 1e-6 * static_cast<double>(columns);
  std::vector<float> shift(rows.size(), 0.0F);
  for (int laser = 0; laser < table.num_lasers; ++laser) {
    const hal::velodyne::LaserCorrection& correction = table.lasers[static_cast<std::size_t>(laser)];
    if (correction.rot_correction_rad != 0.0) return {};
    const auto row = static_cast<std::size_t>(
        std::find(rows.begin(), rows.end(), static_cast<float>(correction.elevation_rad)) - rows.begin());
    shift[row] = static_cast<float>(timing.channel_offset_us[static_cast<std::size_t>(laser)] * columns_per_us);
  }
  return shift;
}

float ElevationOf(const Eigen::Vector3f& p) { return std::atan2(p.z(), std::hypot(p.x(), p.y())); }

bool IsFinitePoint(const Eigen::Vector3f& p) { return p.allFinite() && p.squaredNorm() > 1e-6F; }

// Keeps the measured points (drops NaN and zero-range returns).
SurfelCloud CloudOfPoints(const std::vector<Eigen::Vector3f>& points) {
  SurfelCloud cloud;
  std::size_t count = 0;
  for (const Eigen::Vector3f& p : points) count += IsFinitePoint(p) ? 1 : 0;
  cloud.Resize(count);
  std::size_t next = 0;
  for (const Eigen::Vector3f& p : points) {
    if (IsFinitePoint(p)) cloud.points[next++] = p;
  }
  return cloud;
}

hal::cloud::DepthImage Subsampled(const hal::cloud::DepthImage& depth, int scale) {
  hal::cloud::DepthImage small;
  small.width = depth.width / scale;
  small.height = depth.height / scale;
  small.depth_m.resize(static_cast<std::size_t>(small.width) * static_cast<std::size_t>(small.height));
  for (int row = 0; row < small.height; ++row) {
    for (int col = 0; col < small.width; ++col) {
      small.depth_m[static_cast<std::size_t>(row) * static_cast<std::size_t>(small.width) + static_cast<std::size_t>(col)] =
          depth.at(row * scale, col * scale);
    }
  }
  return small;
}

}  // namespace

std::string_view SensorModelName(SensorModel sensor) {
  for (const SensorName& entry : kSensorNames) {
    if (entry.sensor == sensor) return entry.name;
  }
  return "unknown";
}

std::optional<SensorModel> ParseSensorModel(std::string_view name) {
  for (const SensorName& entry : kSensorNames) {
    if (entry.name == name) return entry.sensor;
  }
  return std::nullopt;
}

SensorModel DetectLidar(const std::vector<Eigen::Vector3f>& points) {
  constexpr float kTolerance = 0.1F * kDegToRad;
  for (const SensorModel sensor : {SensorModel::kHdl32e, SensorModel::kVlp16, SensorModel::kVlp32c}) {
    const std::vector<float> rows = RowElevations(sensor);
    std::size_t measured = 0, matching = 0;
    for (std::size_t i = 0; i < points.size(); i += 7) {  // a sample is plenty
      if (!IsFinitePoint(points[i])) continue;
      ++measured;
      const float e = ElevationOf(points[i]);
      const bool near_a_laser = std::any_of(rows.begin(), rows.end(), [&](float r) { return std::abs(r - e) < kTolerance; });
      matching += near_a_laser ? 1 : 0;
    }
    if (measured > 0 && static_cast<double>(matching) >= 0.95 * static_cast<double>(measured)) return sensor;
  }
  return SensorModel::kUnorganized;
}

SensorModel SensorModelOf(hal::velodyne::Model model) {
  switch (model) {
    case hal::velodyne::Model::kVlp16: return SensorModel::kVlp16;
    case hal::velodyne::Model::kHdl32e: return SensorModel::kHdl32e;
    case hal::velodyne::Model::kVlp32c: return SensorModel::kVlp32c;
  }
  return SensorModel::kAuto;
}

RangeProjection LidarProjection(SensorModel sensor, int columns, double rotation_rpm) {
  if (sensor == SensorModel::kKitti64) {
    // KITTI's archive has no laser table: 64 equal rows over the HDL-64E's +2 .. -24.9 deg.
    return RangeProjection::SphericalBinned(columns, 64, -24.9F * kDegToRad, 2.0F * kDegToRad);
  }
  return RangeProjection::Spherical({columns, RowElevations(sensor), FiringColumnShifts(sensor, columns, rotation_rpm)});
}

RangeFrame UnprojectDepth(const hal::cloud::DepthImage& depth, const RangeFrameOptions& options, int scale) {
  RangeFrame frame;
  frame.sensor = SensorModel::kPinhole;
  scale = std::max(scale, 1);
  const auto inverse_scale = 1.0F / static_cast<float>(scale);
  // Pixel k of the subsampled image is pixel k * scale of the original: u' = u / scale.
  const PinholeIntrinsics& full = options.intrinsics;
  const PinholeIntrinsics intrinsics{depth.width / scale, depth.height / scale, full.fx * inverse_scale,
                                     full.fy * inverse_scale, full.cx * inverse_scale, full.cy * inverse_scale};
  frame.projection = RangeProjection::Pinhole(intrinsics);
  CloudFromDepth(scale == 1 ? depth : Subsampled(depth, scale), frame.projection, options.max_depth_m, frame.cloud,
                 frame.image);
  return frame;
}

RangeFrame FrameFromDepth(const hal::cloud::DepthImage& depth, const RangeFrameOptions& options) {
  RangeFrame frame = UnprojectDepth(depth, options, options.image_scale);
  SurfaceStatistics(options.depth_statistics).Compute(frame.projection, frame.image, frame.cloud);
  frame.statistics_radius_m = options.depth_statistics.radius_m;
  return frame;
}

RangeFrame FrameFromCloud(const hal::cloud::PointCloud& cloud, SensorModel sensor, const RangeFrameOptions& options) {
  RangeFrame frame;
  frame.sensor = sensor == SensorModel::kAuto ? DetectLidar(cloud.points) : sensor;
  frame.cloud = CloudOfPoints(cloud.points);
  if (frame.sensor == SensorModel::kUnorganized || frame.sensor == SensorModel::kPinhole) {
    frame.sensor = SensorModel::kUnorganized;
    ComputeNeighbourStatistics(options.unorganized_statistics, options.viewpoint, frame.cloud);
    frame.statistics_radius_m = options.unorganized_statistics.radius_m;
    return frame;
  }
  frame.projection = LidarProjection(frame.sensor, options.lidar_columns);
  frame.image.Build(frame.projection, frame.cloud.points, {}, Eigen::Isometry3f::Identity());
  SurfaceStatistics(options.lidar_statistics).Compute(frame.projection, frame.image, frame.cloud);
  frame.statistics_radius_m = options.lidar_statistics.radius_m;
  return frame;
}

void RefitStatistics(const RangeFrameOptions& options, float radius_m, RangeFrame& frame) {
  frame.cloud.Resize(frame.cloud.size());  // every normal undefined until fitted again
  frame.statistics_radius_m = radius_m;
  if (!frame.organized()) {
    SurfaceStatisticsOptions statistics = options.unorganized_statistics;
    statistics.radius_m = radius_m;
    ComputeNeighbourStatistics(statistics, options.viewpoint, frame.cloud);
    return;
  }
  SurfaceStatisticsOptions statistics =
      frame.sensor == SensorModel::kPinhole ? options.depth_statistics : options.lidar_statistics;
  statistics.radius_m = radius_m;
  SurfaceStatistics(statistics).Compute(frame.projection, frame.image, frame.cloud);
}

Result<RangeFrame> LoadRangeFrame(const std::filesystem::path& path, const RangeFrameOptions& options) {
  const std::string extension = path.extension().string();
  if (extension == ".png") {
    auto depth = hal::cloud::ReadTumDepthPng(path, options.depth_scale);
    if (!depth.ok()) return depth.error();
    return FrameFromDepth(*depth, options);
  }
  Result<hal::cloud::PointCloud> cloud = MakeError(path.string() + ": unknown range file type '" + extension +
                                                   "' (expected .png, .pcd, .ply or .bin)");
  if (extension == ".pcd") cloud = hal::cloud::ReadPcd(path);
  if (extension == ".ply") cloud = hal::cloud::ReadPly(path);
  if (extension == ".bin") cloud = hal::cloud::ReadKittiBin(path);
  if (!cloud.ok()) return cloud.error();
  SensorModel sensor = options.sensor;
  if (sensor == SensorModel::kAuto && extension == ".bin") sensor = SensorModel::kKitti64;
  if (sensor == SensorModel::kAuto && extension == ".ply") sensor = SensorModel::kUnorganized;
  return FrameFromCloud(*cloud, sensor, options);
}

}  // namespace flat2d::maps::range3d
