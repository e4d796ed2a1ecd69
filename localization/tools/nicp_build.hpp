// `flat2d-map build --mode nicp depth.txt`: a depth sequence tracked by NICP or SNICP
// (thesis 5.1-5.3), written as a TUM trajectory and a PLY model. The first frame is the
// world; each frame's guess is the previous motion (a constant-velocity camera).
//
// Frame to model (the default, 5.1.4): each frame registered against the merged model
// rendered from the last pose, then merged into it (registration/model_tracker.hpp); the
// PLY is the model. Frame to frame: each frame registered to the one before it and the
// poses chained, world_T_k = world_T_{k-1} T; the PLY samples every 10th frame. Either
// way a failed registration keeps the guess and is counted.
#pragma once

#include <filesystem>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/registration/model_tracker.hpp"
#include "localization/registration/nicp_options.hpp"
#include "localization/registration/snicp.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::tools {

struct NicpBuildOptions {
  registration::RegistrationMethod method = registration::RegistrationMethod::kNicp;
  registration::NicpOptions nicp;
  maps::range3d::RangeFrameOptions frames;
  bool snicp = false;             // SNICP (5.2) instead of `method`
  registration::SnicpOptions snicp_options;  // its pyramid, relative to frames.image_scale
  // Frame to frame NICP: coarse-to-fine statistics radii (RegisterFramesOverRadii), the
  // first being frames.depth_statistics.radius_m; one entry: that radius alone. The model
  // tracker fits over the first, and with model_fine_radius refines over the last
  // (ModelTrackerOptions::fine_statistics): on fr1/rpy that halves the ATE at 160x120 and
  // 320x240 but costs 6 mm of it at 640x480 (docs/benchmarks.md, "The model tracker over
  // a fine radius"), so it is not the default.
  std::vector<float> frame_radii{0.1F, registration::kDepthFineRadiusM};
  bool model_fine_radius = false;
  bool constant_velocity = true;  // false: every pair starts from identity
  bool frame_to_model = true;     // false: frame to frame
  maps::range3d::SurfelModelOptions model;
  int max_frames = 0;             // 0: the whole list
  // Frame to frame, the PLY model: the points of every model_every-th frame, every
  // model_stride-th of them.
  int model_every = 10;
  int model_stride = 8;
};

struct NicpBuildSummary {
  int frames = 0;
  int failures = 0;
  std::vector<double> frame_ms;         // per registered frame: its statistics + the registration
  std::vector<double> registration_ms;  // the registration alone
  std::vector<double> load_ms;          // reading and decoding the file
  std::vector<double> merge_ms;         // frame to model: rendering the reference + merging
  std::size_t model_points = 0;
};

// Writes out_dir/trajectory.tum (world_T_camera per frame, the list's stamps) and
// out_dir/model.ply.
Result<NicpBuildSummary> BuildFromDepthList(const std::filesystem::path& list, const NicpBuildOptions& options,
                                            const std::filesystem::path& out_dir);

}  // namespace flat2d::localization::tools
