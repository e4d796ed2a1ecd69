#include "localization/tools/nicp_build.hpp"

#include <chrono>
#include <optional>

#include "hal/cloud/ply_writer.hpp"
#include "hal/cloud/tum_depth_png.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/registration/rigid_transform.hpp"

namespace flat2d::localization::tools {

namespace {

using Clock = std::chrono::steady_clock;

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

// One frame made ready: SNICP's pyramid, or NICP's one level with eigen statistics.
registration::SnicpFrame PrepareFrame(const hal::cloud::DepthImage& depth, const NicpBuildOptions& options,
                                      const registration::SnicpOptions& snicp) {
  if (options.snicp) return registration::MakeSnicpFrame(depth, options.frames, snicp);
  registration::SnicpFrame frame;
  frame.levels.push_back(maps::range3d::FrameFromDepth(depth, options.frames));
  return frame;
}

registration::ModelTrackerOptions TrackerOptions(const NicpBuildOptions& options, const registration::SnicpOptions& snicp) {
  registration::ModelTrackerOptions tracker;
  tracker.nicp = options.nicp;
  tracker.nicp.metric = registration::MetricOf(options.method);
  tracker.model = options.model;
  if (options.snicp) {
    tracker.scales = snicp.scales;
    tracker.iterations_per_level = snicp.iterations_per_level;
  } else {
    tracker.scales = {1};
    tracker.iterations_per_level = options.nicp.iterations;
    if (options.model_fine_radius && options.frame_radii.size() > 1) {
      tracker.fine_statistics = options.frames.depth_statistics;
      tracker.fine_statistics->radius_m = options.frame_radii.back();
    }
  }
  return tracker;
}

// Registers `frame` to the one before it, from `guess`: previous_T_current.
registration::FrameRegistration RegisterToPrevious(const registration::SnicpFrame& previous,
                                                   const registration::SnicpFrame& frame,
                                                   const Eigen::Isometry3d& guess, const NicpBuildOptions& options,
                                                   const registration::SnicpOptions& snicp) {
  if (options.snicp) return registration::RegisterSnicp(previous, frame, guess, options.nicp, snicp);
  if (options.frame_radii.size() < 2) {
    return registration::RegisterFrames(previous.levels.back(), frame.levels.back(), guess, options.method, options.nicp);
  }
  // Refitting changes the frames, and the kept one must start the next pair at the first radius.
  maps::range3d::RangeFrame target = previous.levels.back(), source = frame.levels.back();
  return registration::RegisterFramesOverRadii(options.frames, options.frame_radii, target, source, guess,
                                               options.method, options.nicp);
}

Status WriteOutputs(const std::filesystem::path& out_dir, const std::vector<hal::trajectory::StampedPose>& trajectory,
                    const std::vector<Eigen::Vector3f>& model_points, const std::vector<Eigen::Vector3f>& model_normals) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) return MakeError(out_dir.string() + ": cannot create (" + error.message() + ")");
  if (Status s = hal::trajectory::WriteTum(trajectory, out_dir / "trajectory.tum"); !s.ok()) return s;
  return hal::cloud::WritePly(out_dir / "model.ply", model_points, model_normals);
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
  const registration::SnicpOptions& snicp = options.snicp_options;
  std::optional<registration::ModelTracker> tracker;  // sized by the first frame's image
  registration::SnicpFrame previous;
  Eigen::Isometry3d world_T_camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  // previous_T_current of the last pair
  for (std::size_t k = 0; k < count; ++k) {
    const hal::cloud::DepthFrame& entry = (*frames)[k];
    const Clock::time_point load_start = Clock::now();
    auto depth = hal::cloud::ReadTumDepthPng(entry.file, options.frames.depth_scale);
    if (!depth.ok()) return depth.error();
    const double load_ms = MillisecondsSince(load_start);
    const Clock::time_point frame_start = Clock::now();
    registration::SnicpFrame frame = PrepareFrame(*depth, options, snicp);
    const Eigen::Isometry3d guess = k > 0 && options.constant_velocity ? motion : Eigen::Isometry3d::Identity();
    bool ok = true;
    double registration_ms = 0.0;
    if (options.frame_to_model) {
      if (!tracker) tracker.emplace(frame.levels.back().projection.intrinsics(), TrackerOptions(options, snicp));
      const registration::TrackedFrame tracked = tracker->Track(frame, world_T_camera, guess);
      registration_ms = tracked.register_ms;
      if (k > 0) summary.merge_ms.push_back(tracked.render_ms + tracked.merge_ms);
      motion = world_T_camera.inverse() * tracked.model_T_camera;  // both rigid
      ok = tracked.merged;
    } else if (k > 0) {
      const registration::FrameRegistration r = RegisterToPrevious(previous, frame, guess, options, snicp);
      ok = r.result.ok();
      registration_ms = 1e3 * r.seconds;
      motion = ok ? r.result.target_T_source : guess;
    }
    if (k > 0) {
      summary.frame_ms.push_back(MillisecondsSince(frame_start));
      summary.registration_ms.push_back(registration_ms);
      summary.load_ms.push_back(load_ms);
      summary.failures += ok ? 0 : 1;
      world_T_camera = registration::Orthonormalized(world_T_camera * motion);
    }
    trajectory.push_back(PoseAt(entry.time_s, world_T_camera));
    if (!options.frame_to_model && options.model_every > 0 && k % static_cast<std::size_t>(options.model_every) == 0) {
      AddToModel(frame.levels.back().cloud, world_T_camera, options.model_stride, model_points, model_normals);
    }
    previous = std::move(frame);
  }
  if (tracker) {
    model_points = tracker->model().cloud().points;
    model_normals = tracker->model().cloud().normals;
  }
  summary.frames = static_cast<int>(count);
  summary.model_points = model_points.size();
  if (Status s = WriteOutputs(out_dir, trajectory, model_points, model_normals); !s.ok()) return s.error();
  return summary;
}

}  // namespace flat2d::localization::tools
