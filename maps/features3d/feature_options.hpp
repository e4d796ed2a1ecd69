// Loading and checking FeatureExtractionOptions (feature_options.proto): the text file, each
// threshold's range checked with a message naming the field, and the surface-statistics
// options the normals step hands to maps/range3d.
#pragma once

#include <filesystem>

#include "hal/common/error.hpp"
#include "maps/features3d/feature_options.pb.h"
#include "maps/range3d/range_frame.hpp"
#include "maps/range3d/surface_statistics.hpp"

namespace flat2d::maps::features3d {

// The first problem of `options`, e.g. "segmentation.min_normal_dot: must be in [-1, 1]".
Status ValidateFeatureOptions(const FeatureExtractionOptions& options);

// Parses a text-format file and validates it; errors carry file:line:column or the field.
Result<FeatureExtractionOptions> LoadFeatureOptions(const std::filesystem::path& path);

// `options` for one sensor model: its entry of vertical.min_points_above_by_sensor, if any,
// becomes vertical.min_points_above.
FeatureExtractionOptions OptionsForSensor(const FeatureExtractionOptions& options, range3d::SensorModel sensor);

// The spherical image the options describe for `sensor`: `columns` columns, aligned with the
// firing sequences at `rotation_rpm` (range3d::LidarProjection).
range3d::RangeProjection ProjectionForSensor(const FeatureExtractionOptions& options, range3d::SensorModel sensor);

// The integral-image statistics of 8.1.3 with these normals options (no disc information:
// the features need only the normal).
range3d::SurfaceStatisticsOptions StatisticsOptions(const NormalOptions& normals);

}  // namespace flat2d::maps::features3d
