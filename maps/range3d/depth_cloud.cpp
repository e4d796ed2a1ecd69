#include "maps/range3d/depth_cloud.hpp"

namespace flat2d::maps::range3d {

void CloudFromDepth(const hal::cloud::DepthImage& depth, const RangeProjection& projection, float max_depth_m,
                    SurfelCloud& cloud, IndexImage& image) {
  std::size_t count = 0;
  for (const float d : depth.depth_m) count += (d > 0.0F && d <= max_depth_m) ? 1 : 0;
  cloud.Resize(count);
  // The image's pixels are the projection's: Build() with identity re-derives each
  // point's own pixel (u, v round-trip exactly through pi and pi^-1).
  std::size_t next = 0;
  for (int row = 0; row < depth.height; ++row) {
    for (int col = 0; col < depth.width; ++col) {
      const float d = depth.at(row, col);
      if (d > 0.0F && d <= max_depth_m) cloud.points[next++] = projection.Unproject(row, col, d);
    }
  }
  image.Build(projection, cloud.points, {}, Eigen::Isometry3f::Identity());
}

}  // namespace flat2d::maps::range3d
