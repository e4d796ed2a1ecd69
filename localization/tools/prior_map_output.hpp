// The last step of every `flat2d-map build` that ends in a prior map: the mosaic cropped to
// what was observed, viewpoint sub-maps along the vehicle's path (what a localizer starting
// there would have seen), the tiled map file, and a preview picture with the trajectory.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/mapping/map_builder.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/prior_map/prior_map_file.hpp"

namespace flat2d::localization::tools {

struct MapOutputOptions {
  maps::PriorMapWriteOptions write;
  double viewpoint_spacing_m = 10.0;  // a viewpoint every this many metres of path; 0: none
  double viewpoint_range_m = 20.0;    // their radius
  std::optional<std::filesystem::path> png;  // the preview: map, trajectory (blue), viewpoints (green)
};

struct MapOutput {
  std::size_t viewpoints = 0;
};

// A 3D build's poses as the map writer's path: each pose a "keyframe" with the distance
// travelled to it; `planar` gets the poses flattened, for the preview.
std::vector<mapping::Keyframe> PathOf(const std::vector<hal::trajectory::StampedPose>& trajectory,
                                      std::vector<evaluation::TimedPose>& planar);

// `path` gives the viewpoints' places (estimate and path_m of each keyframe or scan);
// `trajectory` is drawn on the preview. Errors name the file that could not be written.
Result<MapOutput> WriteBuiltMap(maps::ClassGrid mosaic, const std::vector<mapping::Keyframe>& path,
                                const std::vector<evaluation::TimedPose>& trajectory,
                                const std::filesystem::path& out, const MapOutputOptions& options);

// A 3D build's map: `mosaic` (the capture gridded at `trajectory`) written as DIR/map.f2m
// with DIR/map.png, viewpoints along the trajectory.
Result<MapOutput> WriteTrajectoryMap(maps::ClassGrid mosaic, const std::vector<hal::trajectory::StampedPose>& trajectory,
                                     const std::filesystem::path& out, const std::string& created_by,
                                     const std::string& source);

}  // namespace flat2d::localization::tools
