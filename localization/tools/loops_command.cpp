#include "localization/tools/loops_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "hal/trajectory/kitti_pose_file.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/evaluation/loop_candidate_eval.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kLoopsUsage = R"(usage:
  flat2d-eval loops (--kitti-poses POSES.txt | --truth T.tum) [options] [--json]

loops: the truth is drifted (a seeded dead reckoning: wheel scale error, yaw bias, noise),
cut into local maps every --piece-length metres of the drifted path, and every map is
searched for loop-closure candidates among the maps before it, (a) by distance between map
centres in the drifted estimate and (b) by trajectory shape (thesis Eq. 6.13). A candidate
is correct when its two maps overlap in truth and its guess of their relative pose is within
--tolerance-m and --tolerance-deg of the truth's. Recall: the revisiting map pairs (at least
half of the newer map's truth path within --revisit-radius of the older map's, in the same
direction, both informative) with a correct candidate. Precision: correct / all candidates.
  --kitti-poses FILE       KITTI odometry ground truth (poses/NN.txt), camera frame
  --truth FILE             a TUM trajectory (world_T_vehicle)
  --piece-length M         default 5
  --drift-seed N           default 1
  --drift-scale F          wheel distance error, fraction (default 0.005)
  --drift-yaw-bias D       deg per metre (default 0.005)
  --drift-yaw-noise D      deg per sqrt(m), 1-sigma (default 0.05)
  --drift-tilt-noise D     roll and pitch, deg per sqrt(m), 1-sigma (default 0.02)
  --drift-scale-noise F    per step, fraction of the step, 1-sigma (default 0.01)
  --radius M               (a)'s search radius (default 10)
  --min-separation M       maps nearer than this along the drive are not loops (default 50)
  --min-spread M           informative: second spread of the map's path (default 0.05)
  --context M              path either side of a map used by the fit (default 15)
  --association-spacing M  associations along each past map, from a random first (default 1.5)
  --seed N                 the random seed (default 1)
  --max-turn-difference D  maps whose own turns differ more are not fitted (deg, default 20)
  --max-rms M              accepted fit's RMS translation error (default 0.3)
  --min-matched M          path length the accepted fit must follow (default 10)
  --drift-bound F          (b) also requires the guess within F x path since the older
                           map of the estimate (default 0: off)
  --revisit-radius M       default 2
  --tolerance-m M          default 1
  --tolerance-deg D        default 5
  --json                   one JSON object: maps, informative_maps, revisits,
                           informative_revisits, opposite_revisits, path_length_m,
                           final_drift_m, and per strategy (distance_, shape_): candidates,
                           correct, precision, recall, revisits_found, shape_seconds
)";

namespace {

constexpr std::string_view kTool = "flat2d-eval";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct LoopsArgs {
  std::string kitti_path, tum_path;
  evaluation::LoopEvalOptions options;
  bool json = false;
};

LoopsArgs ParseLoopsArgs(int argc, char** argv) {
  LoopsArgs a;
  auto& candidates = a.options.candidates;
  auto& drift = a.options.drift;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto number = [&] { return maps::cli::ParseNumber(kTool, arg, value()); };
    auto count = [&](std::int64_t min) { return maps::cli::ParseInteger(kTool, arg, value(), min, 1 << 30); };
    if (arg == "--kitti-poses") a.kitti_path = value();
    else if (arg == "--truth") a.tum_path = value();
    else if (arg == "--piece-length") a.options.piece_length_m = number();
    else if (arg == "--drift-seed") drift.seed = static_cast<std::uint32_t>(count(0));
    else if (arg == "--drift-scale") drift.scale_error = number();
    else if (arg == "--drift-yaw-bias") drift.yaw_bias_deg_per_m = number();
    else if (arg == "--drift-yaw-noise") drift.yaw_noise_deg_per_sqrt_m = number();
    else if (arg == "--drift-tilt-noise") drift.tilt_noise_deg_per_sqrt_m = number();
    else if (arg == "--drift-scale-noise") drift.scale_noise = number();
    else if (arg == "--radius") candidates.distance_radius_m = number();
    else if (arg == "--min-separation") candidates.min_path_separation_m = number();
    else if (arg == "--min-spread") candidates.min_spread_m = number();
    else if (arg == "--context") candidates.context_m = number();
    else if (arg == "--association-spacing") candidates.association_spacing_m = number();
    else if (arg == "--seed") candidates.random_seed = static_cast<std::uint32_t>(count(0));
    else if (arg == "--max-turn-difference") candidates.max_turn_difference_rad = number() * M_PI / 180.0;
    else if (arg == "--max-rms") candidates.max_rms_translation_m = number();
    else if (arg == "--min-matched") candidates.min_matched_m = number();
    else if (arg == "--drift-bound") candidates.drift_fraction = number();
    else if (arg == "--revisit-radius") a.options.revisit_radius_m = number();
    else if (arg == "--tolerance-m") a.options.tolerance_m = number();
    else if (arg == "--tolerance-deg") a.options.tolerance_deg = number();
    else if (arg == "--json") a.json = true;
    else Fail(1, "loops: unknown argument " + std::string(arg) + "\n" + kLoopsUsage);
  }
  if (a.kitti_path.empty() == a.tum_path.empty()) Fail(1, std::string("loops needs one of --kitti-poses, --truth\n") + kLoopsUsage);
  if (a.options.piece_length_m <= 0.0) Fail(1, "loops: --piece-length must be positive");
  return a;
}

std::vector<Eigen::Isometry3d> ReadTruth(const LoopsArgs& args) {
  std::vector<Eigen::Isometry3d> truth;
  if (!args.kitti_path.empty()) {
    auto poses = hal::trajectory::ReadKittiPoses(args.kitti_path);
    if (!poses.ok()) Fail(2, poses.error().message);
    for (const auto& pose : *poses) truth.push_back(hal::trajectory::VehicleFromKittiCamera(pose));
  } else {
    auto poses = hal::trajectory::ReadTum(args.tum_path);
    if (!poses.ok()) Fail(2, poses.error().message);
    for (const auto& pose : *poses) truth.push_back(pose.world_T_body);
  }
  if (truth.size() < 2) Fail(2, "loops: the trajectory has fewer than two poses");
  return truth;
}

void PrintJson(const evaluation::LoopEvalReport& r) {
  const auto strategy = [&](const char* name, const evaluation::CandidateScore& s) {
    std::printf(",\"%s_candidates\":%d,\"%s_correct\":%d,\"%s_precision\":%.4f,\"%s_recall\":%.4f,\"%s_revisits_found\":%d",
                name, s.candidates, name, s.correct, name, s.precision(), name, r.recall(s), name, s.revisits_found);
  };
  std::printf("{\"poses\":%d,\"path_length_m\":%.1f,\"final_drift_m\":%.2f,\"maps\":%d,\"informative_maps\":%d,"
              "\"revisits\":%d,\"informative_revisits\":%d,\"opposite_revisits\":%d",
              r.poses, r.path_length_m, r.final_drift_m, r.maps, r.informative_maps, r.revisits, r.informative_revisits,
              r.opposite_revisits);
  strategy("distance", r.distance);
  strategy("shape", r.shape);
  std::printf(",\"shape_seconds\":%.3f}\n", r.shape_seconds);
}

void PrintText(const evaluation::LoopEvalReport& r) {
  std::printf("%d poses, %.0f m; drifted estimate %.1f m off at the end\n", r.poses, r.path_length_m, r.final_drift_m);
  std::printf("%d local maps, %d informative; %d revisiting pairs (%d of informative maps), %d in the opposite direction\n",
              r.maps, r.informative_maps, r.revisits, r.informative_revisits, r.opposite_revisits);
  const auto line = [&](const char* name, const evaluation::CandidateScore& s) {
    std::printf("%-17s %6d candidates, %6d correct: precision %.3f, recall %.3f (%d of %d; %d of all %d revisits)\n", name,
                s.candidates, s.correct, s.precision(), r.recall(s), s.revisits_found, r.informative_revisits,
                s.all_revisits_found, r.revisits);
  };
  line("distance", r.distance);
  line("trajectory shape", r.shape);
  std::printf("trajectory-shape search: %.2f s\n", r.shape_seconds);
}

}  // namespace

int LoopsCommand(int argc, char** argv) {
  const LoopsArgs args = ParseLoopsArgs(argc, argv);
  const std::vector<Eigen::Isometry3d> truth = ReadTruth(args);
  const evaluation::LoopEvalReport report = evaluation::EvaluateLoopCandidates(truth, args.options);
  if (args.json) PrintJson(report);
  else PrintText(report);
  return 0;
}

}  // namespace flat2d::localization::tools
