#include "localization/tools/nicp_build.hpp"

#include <chrono>

#include "hal/cloud/ply_writer.hpp"
#include "hal/cloud/tum_depth_png.hpp"
#include "hal/trajectory/tum_file.hpp"

namespace flat2d::localization::tools {

namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

hal::trajectory::StampedPose PoseAt(double time_s, const Eigen::Isometry3d& world_T_camera) {
  return {static_cast<TimeNs>(std::llround(time_s * 1e9)), world_T_camera};
}

void AddToModel(const maps::range3d::SurfelCloud& cloud, const Eigen::Isometry3d& world_T_camera, int stride,
                std::vector<Eigen::Vector3f>& points, std::vector<Eigen::Vector3f>& normals) {
  const Eigen::Isometry3f pose = world_T_camera.cast<float>();
  for (std::size_t i = 0; i < cloud.size(); i += static_cast<std::size_t>(stride)) {
    if (!cloud.has_normal(i)) continue;
    points.push_back(pose * cloud.points[i]);
    normals.push_back(pose.linear() * cloud.normals[i]);
  }
}

}  // namespace

Result<NicpBuildSummary> BuildFromDepthList(const std::filesystem::path& list, const NicpBuildOptions& options,
                                            const std::filesystem::path& out_dir) {
  auto frames = hal::cloud::ReadTumAssociationList(list);
  if (!frames.ok()) return frames.error();
  const std::size_t count = options.max_frames > 0 ? std::min(frames->size(), static_cast<std::size_t>(options.max_frames))
                                                   : frames->size();
  if (count == 0) return MakeError(list.string() + ": no depth frame listed");

  NicpBuildSummary summary;
  std::vector<hal::trajectory::StampedPose> trajectory;
  std::vector<Eigen::Vector3f> model_points, model_normals;
  maps::range3d::RangeFrame previous;
  registration::SnicpFrame previous_pyramid;
  const registration::SnicpOptions snicp;
  Eigen::Isometry3d world_T_camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  // previous_T_current of the last pair
  for (std::size_t k = 0; k < count; ++k) {
    const hal::cloud::DepthFrame& entry = (*frames)[k];
    const Clock::time_point load_start = Clock::now();
    auto depth = hal::cloud::ReadTumDepthPng(entry.file, options.frames.depth_scale);
    if (!depth.ok()) return depth.error();
    const double load_ms = MsSince(load_start);
    const Clock::time_point frame_start = Clock::now();
    registration::SnicpFrame pyramid;
    maps::range3d::RangeFrame current;
    if (options.snicp) {
      pyramid = registration::MakeSnicpFrame(*depth, options.frames, snicp);
      current = pyramid.levels.back();
    } else {
      current = maps::range3d::FrameFromDepth(*depth, options.frames);
    }
    if (k > 0) {
      const Eigen::Isometry3d guess = options.constant_velocity ? motion : Eigen::Isometry3d::Identity();
      const registration::FrameRegistration r =
          options.snicp ? registration::RegisterSnicp(previous_pyramid, pyramid, guess, options.nicp, snicp)
                        : registration::RegisterFrames(previous, current, guess, options.method, options.nicp);
      summary.frame_ms.push_back(MsSince(frame_start));
      summary.registration_ms.push_back(1e3 * r.seconds);
      summary.load_ms.push_back(load_ms);
      if (r.result.ok()) {
        motion = r.result.target_T_source;
      } else {
        ++summary.failures;
        motion = guess;
      }
      world_T_camera = world_T_camera * motion;
    }
    trajectory.push_back(PoseAt(entry.time_s, world_T_camera));
    if (options.model_every > 0 && k % static_cast<std::size_t>(options.model_every) == 0) {
      AddToModel(current.cloud, world_T_camera, options.model_stride, model_points, model_normals);
    }
    previous = std::move(current);
    previous_pyramid = std::move(pyramid);
  }
  summary.frames = static_cast<int>(count);
  summary.model_points = model_points.size();
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) return MakeError(out_dir.string() + ": cannot create (" + error.message() + ")");
  if (Status s = hal::trajectory::WriteTum(trajectory, out_dir / "trajectory.tum"); !s.ok()) return s.error();
  if (Status s = hal::cloud::WritePly(out_dir / "model.ply", model_points, model_normals); !s.ok()) return s.error();
  return summary;
}

}  // namespace flat2d::localization::tools
