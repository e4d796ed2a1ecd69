#include "maps/tools/inspect_render.hpp"

#include <vector>

#include "maps/render/png_writer.hpp"

namespace flat2d::maps {

Result<std::size_t> RenderRevolutionPng(std::span<const hal::velodyne::Fan> fans,
                                        const TopDownOptions& options,
                                        const std::filesystem::path& png_path) {
  std::vector<TopDownPoint> points;
  for (const hal::velodyne::Fan& fan : fans) {
    for (int laser = 0; laser < fan.num_lasers; ++laser) {
      const hal::velodyne::LaserReturn& r = fan.returns[static_cast<std::size_t>(laser)];
      if (r.range_m <= 0.0f) continue;
      points.push_back({r.xyz.x(), r.xyz.y(), r.xyz.z(), static_cast<float>(r.intensity)});
    }
  }
  Result<TopDownRender> render = RenderTopDown(points, options);
  if (!render.ok()) return render.error();
  if (Status written = WritePng(render->image, png_path); !written.ok()) return written.error();
  return render->drawn;
}

}  // namespace flat2d::maps
