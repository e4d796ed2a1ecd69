#include "maps/range3d/neighbour_statistics.hpp"

#include <utility>
#include <vector>

#include "maps/range3d/point_kdtree.hpp"

namespace flat2d::maps::range3d {

void ComputeNeighbourStatistics(const SurfaceStatisticsOptions& options, const Eigen::Vector3f& viewpoint,
                                SurfelCloud& cloud) {
  const PointKdTree<3> tree(cloud.points, nullptr, 0.0F);
  std::vector<std::pair<std::uint32_t, float>> neighbours;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;
    tree.WithinRadius(cloud.points[i].data(), options.radius_m, neighbours);
    if (static_cast<int>(neighbours.size()) < options.min_points) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (const auto& [member, distance_squared] : neighbours) {
      const Eigen::Vector3d p = cloud.points[member].cast<double>();
      sum += p;
      second += p * p.transpose();
    }
    const double n = static_cast<double>(neighbours.size());
    const Eigen::Vector3d mean = sum / n;
    AssignSurface(second / n - mean * mean.transpose(), viewpoint - cloud.points[i], options, i, cloud);
  }
}

}  // namespace flat2d::maps::range3d
