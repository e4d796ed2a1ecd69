#include "maps/features3d/feature_options.hpp"

#include <cmath>
#include <string>

#include "hal/config/text_proto.hpp"

namespace flat2d::maps::features3d {
namespace {

// Keeps the first problem found; every check names its field.
class Checker {
 public:
  void Positive(const char* field, double value) {
    if (!(value > 0.0 && std::isfinite(value))) Fail(field, "must be positive and finite");
  }
  void NonNegative(const char* field, double value) {
    if (!(value >= 0.0 && std::isfinite(value))) Fail(field, "must be >= 0 and finite");
  }
  void Fraction(const char* field, double value) {
    if (!(value > 0.0 && value < 1.0)) Fail(field, "must be in (0, 1)");
  }
  void AtLeast(const char* field, unsigned value, unsigned low) {
    if (value < low) Fail(field, "must be at least " + std::to_string(low));
  }
  void Require(bool condition, const char* field, const std::string& what) {
    if (!condition) Fail(field, what);
  }
  Status status() const { return error_.empty() ? Status::Ok() : Status(MakeError(error_)); }

 private:
  void Fail(const char* field, const std::string& what) {
    if (error_.empty()) error_ = std::string(field) + ": " + what;
  }
  std::string error_;
};

void CheckVertical(const VerticalRemovalOptions& vertical, Checker& check) {
  check.Positive("vertical.ground_radius_m", vertical.ground_radius_m());
  check.AtLeast("vertical.min_points_above", vertical.min_points_above(), 1);
  for (const auto& [sensor, points] : vertical.min_points_above_by_sensor()) {
    const auto model = range3d::ParseSensorModel(sensor);
    check.Require(model.has_value() && *model != range3d::SensorModel::kAuto && *model != range3d::SensorModel::kPinhole &&
                      *model != range3d::SensorModel::kUnorganized,
                  "vertical.min_points_above_by_sensor", "unknown LiDAR model \"" + sensor + "\" (vlp16, hdl32e, vlp32c, kitti64)");
    check.AtLeast("vertical.min_points_above_by_sensor", points, 1);
  }
}

void CheckNormals(const NormalOptions& normals, Checker& check) {
  check.Positive("normals.radius_m", normals.radius_m());
  check.AtLeast("normals.min_points", normals.min_points(), 3);
  check.AtLeast("normals.max_half_size_px", normals.max_half_size_px(), 1);
  check.Require(normals.max_half_size_px() <= 256, "normals.max_half_size_px", "must be at most 256");
  check.Fraction("normals.depth_jump_ratio", normals.depth_jump_ratio());
  check.Require(normals.line_max_middle_share() >= 0.0 && normals.line_max_middle_share() < 1.0 / 3.0,
                "normals.line_max_middle_share", "must be in [0, 1/3)");
}

void CheckSegmentation(const SegmentationOptions& segmentation, Checker& check) {
  check.Positive("segmentation.max_distance_m", segmentation.max_distance_m());
  check.NonNegative("segmentation.max_distance_per_m", segmentation.max_distance_per_m());
  check.Require(segmentation.min_normal_dot() >= -1.0 && segmentation.min_normal_dot() <= 1.0,
                "segmentation.min_normal_dot", "must be in [-1, 1]");
  check.AtLeast("segmentation.min_cluster_points", segmentation.min_cluster_points(), 2);
  check.AtLeast("segmentation.neighbour_cols", segmentation.neighbour_cols(), 1);
  check.Require(segmentation.min_rows() <= 64, "segmentation.min_rows", "must be at most 64");
  check.NonNegative("segmentation.pole_max_width_m", segmentation.pole_max_width_m());
  check.NonNegative("segmentation.pole_join_distance_m", segmentation.pole_join_distance_m());
  check.Require(segmentation.neighbour_cols() <= 16, "segmentation.neighbour_cols", "must be at most 16");
}

void CheckFitting(const FittingOptions& fitting, Checker& check) {
  check.Fraction("fitting.line_max_spread", fitting.line_max_spread());
  check.Positive("fitting.line_max_residual_m", fitting.line_max_residual_m());
  check.Fraction("fitting.plane_max_flatness", fitting.plane_max_flatness());
  check.Positive("fitting.plane_max_residual_m", fitting.plane_max_residual_m());
  check.AtLeast("fitting.min_plane_points", fitting.min_plane_points(), 3);
  check.NonNegative("fitting.min_plane_width_m", fitting.min_plane_width_m());
  check.NonNegative("fitting.line_axis_min_radius_m", fitting.line_axis_min_radius_m());
  check.NonNegative("fitting.min_plane_height_m", fitting.min_plane_height_m());
  check.Require(fitting.line_min_roundness() >= 0.0 && fitting.line_min_roundness() < 1.0, "fitting.line_min_roundness",
                "must be in [0, 1)");
}

}  // namespace

Status ValidateFeatureOptions(const FeatureExtractionOptions& options) {
  Checker check;
  CheckVertical(options.vertical(), check);
  CheckNormals(options.normals(), check);
  CheckSegmentation(options.segmentation(), check);
  CheckFitting(options.fitting(), check);
  check.NonNegative("max_range_m", options.max_range_m());
  check.AtLeast("columns", options.columns(), 360);
  check.Require(options.columns() <= 8192, "columns", "must be at most 8192");
  // Velodyne sensors turn at 300-1200 rpm; 0 turns the firing alignment off.
  check.Require(options.rotation_rpm() >= 0.0 && options.rotation_rpm() <= 1200.0, "rotation_rpm",
                "must be in [0, 1200]");
  return check.status();
}

Result<FeatureExtractionOptions> LoadFeatureOptions(const std::filesystem::path& path) {
  FeatureExtractionOptions options;
  if (Status loaded = hal::config::LoadTextProto(path, options); !loaded.ok()) return loaded.error();
  if (Status valid = ValidateFeatureOptions(options); !valid.ok()) {
    return MakeError(path.string() + ": " + valid.error().message);
  }
  return options;
}

range3d::RangeProjection ProjectionForSensor(const FeatureExtractionOptions& options, range3d::SensorModel sensor) {
  return range3d::LidarProjection(sensor, static_cast<int>(options.columns()), options.rotation_rpm());
}

FeatureExtractionOptions OptionsForSensor(const FeatureExtractionOptions& options, range3d::SensorModel sensor) {
  FeatureExtractionOptions resolved = options;
  const auto& by_sensor = options.vertical().min_points_above_by_sensor();
  const auto it = by_sensor.find(std::string(range3d::SensorModelName(sensor)));
  if (it != by_sensor.end()) resolved.mutable_vertical()->set_min_points_above(it->second);
  return resolved;
}

range3d::SurfaceStatisticsOptions StatisticsOptions(const NormalOptions& normals) {
  range3d::SurfaceStatisticsOptions statistics;
  statistics.radius_m = static_cast<float>(normals.radius_m());
  statistics.min_points = static_cast<int>(normals.min_points());
  statistics.max_half_size_px = static_cast<int>(normals.max_half_size_px());
  statistics.depth_jump_ratio = static_cast<float>(normals.depth_jump_ratio());
  statistics.line_max_middle_share = static_cast<float>(normals.line_max_middle_share());
  return statistics;
}

}  // namespace flat2d::maps::features3d
