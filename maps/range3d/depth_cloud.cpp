#include "maps/range3d/depth_cloud.hpp"

namespace flat2d::maps::range3d {

void CloudFromDepth(const hal::cloud::DepthImage& depth, const RangeProjection& projection, float max_depth_m,
                    SurfelCloud& cloud, IndexImage& image) {
  std::size_t count = 0;
  for (const float d : depth.depth_m) count += (d > 0.0F && d <= max_depth_m) ? 1 : 0;
  cloud.Resize(count);
  // The image's pixels are the projection's (u, v round-trip exactly through pi and
  // pi^-1), so each point's pixel is set, not re-projected.
  image.Clear(projection.rows(), projection.cols());
  std::size_t next = 0;
  for (int row = 0; row < depth.height; ++row) {
    for (int col = 0; col < depth.width; ++col) {
      const float d = depth.at(row, col);
      if (!(d > 0.0F && d <= max_depth_m)) continue;
      image.Set(row, col, static_cast<std::int32_t>(next), d);
      cloud.points[next++] = projection.Unproject(row, col, d);
    }
  }
}

}  // namespace flat2d::maps::range3d
