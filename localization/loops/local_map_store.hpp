// Local maps on disk (thesis 6.3: "only the graph stays in memory"; Fig. 6.6: a local map is
// its points and its internal trajectory). In a directory:
//   map_NNNN.ply  the map's points and normals in its own frame, thinned to the first point
//                 in each voxel (binary PLY: MeshLab and CloudCompare open it);
//   map_NNNN.tum  its internal trajectory, map_T_vehicle per revolution (TUM format).
// Reading a map back recomputes its surface statistics with a KD-tree (the points of a
// merged model are unorganized, and the thinning changed their neighbourhoods), each
// normal turned to the side of the stored one.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Geometry>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "maps/range3d/surface_statistics.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::localization::loops {

struct LocalMapStoreOptions {
  double voxel_m = 0.1;  // one point kept per voxel
  // R of the statistics when a map is read back: the LiDAR drive's 0.3 m (nicp_drive_build).
  maps::range3d::SurfaceStatisticsOptions statistics{0.3F, 8, 32, 0.1F, 0.02F, 1e-3F, 0.0F};
};

class LocalMapStore {
 public:
  LocalMapStore(std::filesystem::path directory, const LocalMapStoreOptions& options);

  // Creates the directory; an error names it when it cannot be created.
  Status Create() const;
  // `points`: the map's points in the world frame with their normals (undefined ones are
  // left out); written in the map's frame.
  Status WritePoints(int index, const maps::range3d::SurfelCloud& points, const Eigen::Isometry3d& world_T_map) const;
  Status WriteTrajectory(int index, const std::vector<hal::trajectory::StampedPose>& map_T_vehicle) const;
  // The map's points (map frame) with statistics. An error names the file.
  Result<maps::range3d::SurfelCloud> ReadPoints(int index) const;
  // The points and normals as stored.
  Result<hal::cloud::PointCloud> ReadStored(int index) const;

  std::filesystem::path PointsPath(int index) const;
  std::filesystem::path TrajectoryPath(int index) const;

 private:
  std::filesystem::path directory_;
  LocalMapStoreOptions options_;
};

}  // namespace flat2d::localization::loops
