#include "localization/evaluation/trajectory_file.hpp"

#include <cmath>
#include <cstdio>

#include "hal/trajectory/tum_file.hpp"
#include "maps/grid/interpolated_poses.hpp"

namespace flat2d::localization::evaluation {

Result<std::vector<TimedPose>> ReadTrajectory(const std::filesystem::path& path) {
  auto poses = hal::trajectory::ReadTum(path);
  if (!poses.ok()) return poses.error();
  std::vector<TimedPose> out;
  out.reserve(poses->size());
  for (const auto& p : *poses) {
    const maps::StampedPose2d flat = maps::Flatten(p.time_ns, p.world_T_body);
    out.push_back({static_cast<double>(p.time_ns) * 1e-9, Se2(flat.position, flat.yaw)});
  }
  return out;
}

Status WriteTrajectory(const std::vector<TimedPose>& trajectory, const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return MakeError(path.string() + ": cannot write");
  std::fprintf(file, "# t x y z qx qy qz qw\n");
  for (const TimedPose& p : trajectory) {
    const double half = 0.5 * p.pose.theta();
    std::fprintf(file, "%.9f %.6f %.6f 0 0 0 %.9f %.9f\n", p.time_s, p.pose.x(), p.pose.y(), std::sin(half),
                 std::cos(half));
  }
  if (std::fclose(file) != 0) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

}  // namespace flat2d::localization::evaluation
