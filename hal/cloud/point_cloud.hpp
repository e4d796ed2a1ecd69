// 3D measurements as range sensors and scan archives deliver them: the vocabulary the
// readers (pcd_file, ply_file, kitti_bin_file, tum_depth_png) return and the range-image
// code in maps/range3d consumes.
//
// A cloud is a list of points in the sensor frame (metres) with optional per-point
// channels. Where the file says how the points were measured (a PCD organized cloud, a
// PLY range_grid, a Velodyne ring field) that structure is kept, because projective
// registration (thesis 5.1.2) needs the sensor's own image layout, not a re-projection.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace flat2d::hal::cloud {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;  // sensor frame, metres; NaN where the file has none
  std::vector<float> intensity;         // empty, or one per point
  std::vector<std::uint16_t> ring;      // empty, or one per point: laser index (PCD "ring")
  std::vector<Eigen::Vector3f> normals;  // empty, or one per point: PLY nx, ny, nz as stored

  // The measurement grid, when the file has one: grid_width x grid_height cells, row-major,
  // each the index of its point in `points` or -1 (no return). PCD organized clouds
  // (HEIGHT > 1) fill it with the identity; a PLY range_grid with its vertex lists.
  int grid_width = 0;
  int grid_height = 0;
  std::vector<std::int32_t> grid;

  bool organized() const { return grid_width > 0 && grid_height > 0; }
};

// A depth image: width x height metres, row-major, 0 where the sensor saw nothing.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth_m;

  float at(int row, int col) const { return depth_m[static_cast<std::size_t>(row) * width + col]; }
};

}  // namespace flat2d::hal::cloud
