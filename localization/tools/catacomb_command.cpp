#include "localization/tools/catacomb_command.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "hal/cloud/ply_writer.hpp"
#include "hal/common/angles.hpp"
#include "hal/trajectory/pose_interpolation.hpp"
#include "localization/evaluation/loop_candidate_eval.hpp"
#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_error_3d.hpp"
#include "localization/graph/g2o_se3_io.hpp"
#include "localization/graph/se3_costs.hpp"
#include "localization/tools/catacomb_build.hpp"
#include "localization/tools/nicp_drive_command.hpp"
#include "localization/tools/prior_map_output.hpp"
#include "maps/grid/structure_grid_config.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

namespace {

constexpr std::string_view kTool = "flat2d-map";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  NicpDriveArgs drive;
  CatacombOptions options;
  std::optional<std::string> closures, truth;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (ParseNicpDriveFlag(argc, argv, i, a.drive)) continue;
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto number = [&] { return maps::cli::ParseNumber(kTool, arg, value()); };
    auto integer = [&](int low, int high) {
      return static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), low, high));
    };
    if (arg == "--local-map-distance") a.drive.options.local_map_distance_m = number();
    else if (arg == "--local-map-angle") a.drive.options.local_map_angle_rad = number();
    else if (arg == "--local-map-overlap") a.drive.options.local_map_min_overlap = number();
    else if (arg == "--continuous-tracking") a.drive.options.continuous_tracking = true;
    else if (arg == "--range-merge-weights") a.drive.options.model.weighting = maps::range3d::DepthWeighting::kInverse;
    else if (arg == "--ambiguity-shift") a.options.validation.ambiguity_shift_m = number();
    else if (arg == "--alias-neighbours") a.options.alias_neighbours = integer(0, 100);
    else if (arg == "--alias-everywhere") a.options.alias_everywhere = true;
    else if (arg == "--no-loops") a.options.distance_candidates = a.options.shape_candidates = false;
    else if (arg == "--no-distance-candidates") a.options.distance_candidates = false;
    else if (arg == "--no-shape-candidates") a.options.shape_candidates = false;
    else if (arg == "--closures") a.closures = value();
    else if (arg == "--inject-false") a.options.injected_false_share = number();
    else if (arg == "--truth") a.truth = value();
    else if (arg == "--break-chain") a.options.break_at_map = integer(1, 1 << 30);
    else Fail(1, "build --mode catacomb DRIVE: unknown argument " + std::string(arg) + "\n" + kCatacombUsage);
  }
  CheckNicpDriveArgs(a.drive, "catacomb", kCatacombUsage);
  if (a.drive.options.local_map_distance_m < 0.0) Fail(1, "build --mode catacomb: --local-map-distance is >= 0");
  if (a.drive.options.local_map_angle_rad < 0.0) Fail(1, "build --mode catacomb: --local-map-angle is >= 0");
  const double overlap = a.drive.options.local_map_min_overlap;
  if (!(overlap >= 0.0 && overlap <= 1.0)) Fail(1, "build --mode catacomb: --local-map-overlap is a share in [0, 1]");
  if (a.options.validation.ambiguity_shift_m < 0.0) Fail(1, "build --mode catacomb: --ambiguity-shift is >= 0 (0: no test)");
  if (a.options.injected_false_share < 0.0 || a.options.injected_false_share >= 1.0) {
    Fail(1, "build --mode catacomb: --inject-false is a share in [0, 1)");
  }
  return a;
}

void Prepare(Args& a) {
  PrepareNicpDrive(a.drive);
  a.options.drive = a.drive.options;
  a.options.out = a.drive.out;
  if (a.closures) {
    auto edits = loops::ReadClosureEdits(*a.closures);
    if (!edits.ok()) Fail(2, edits.error().message);
    a.options.edits = std::move(*edits);
  }
}

// The truth's pose at each stamp (interpolated; nearest outside its time).
std::vector<Eigen::Isometry3d> TruthAt(const std::vector<hal::trajectory::StampedPose>& truth,
                                       const std::vector<hal::trajectory::StampedPose>& at) {
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& pose : at) {
    const auto interpolated = evaluation::InterpolatedPose(truth, pose.time_ns, std::numeric_limits<TimeNs>::max());
    const bool before = pose.time_ns < truth.front().time_ns;
    poses.push_back(interpolated ? *interpolated : before ? truth.front().world_T_body : truth.back().world_T_body);
  }
  return poses;
}

struct ClosureTruth {
  int revisits = 0;
  int informative_revisits = 0;
  int kept = 0, correct = 0, revisits_found = 0;
  double rpe_m = 0.0, rpe_rad = 0.0;                    // consecutive local maps, optimized
  double tracking_rpe_m = 0.0, tracking_rpe_rad = 0.0;  // ... as tracked
  std::vector<std::pair<double, double>> closure_errors;  // per record: metres, degrees
};

// The mean error of consecutive maps' relative poses against the truth's (sensor frames).
std::pair<double, double> LocalMapRpe(const std::vector<Eigen::Isometry3d>& world_T_map,
                                      const std::vector<Eigen::Isometry3d>& truth_T_map) {
  double sum_m = 0.0, sum_rad = 0.0;
  for (std::size_t i = 0; i + 1 < world_T_map.size(); ++i) {
    const Eigen::Isometry3d error = (truth_T_map[i].inverse() * truth_T_map[i + 1]).inverse() *
                                    (world_T_map[i].inverse() * world_T_map[i + 1]);
    sum_m += error.translation().norm();
    sum_rad += Eigen::AngleAxisd(error.linear()).angle();
  }
  const double pairs = std::max<double>(1.0, static_cast<double>(world_T_map.size()) - 1.0);
  return {sum_m / pairs, sum_rad / pairs};
}

// The kept closures against the truth: the truth's sensor poses at the revolutions, cut as
// the build cut its maps (loop_candidate_eval.hpp's revisits and tolerances).
ClosureTruth JudgeClosures(const Args& a, const CatacombResult& r, const std::vector<hal::trajectory::StampedPose>& truth) {
  const Eigen::Isometry3d vehicle_T_sensor = maps::VehicleFromSensor(a.options.drive.grid.mounting());
  std::vector<Eigen::Isometry3d> sensor = TruthAt(truth, r.drive.trajectory);
  for (auto& pose : sensor) pose = pose * vehicle_T_sensor;
  evaluation::LocalMapCut cut{r.maps, r.first_revolution, r.last_revolution};
  evaluation::LoopEvalOptions options;
  options.candidates = a.options.candidates;
  options.tolerance_m = 0.3;
  options.tolerance_deg = 1.0;
  const evaluation::RevisitTruth revisits = evaluation::RevisitsOf(sensor, cut, options);
  ClosureTruth t;
  std::vector<Eigen::Isometry3d> optimized, tracked, truth_maps;
  for (std::size_t i = 0; i < r.maps.size(); ++i) {
    optimized.push_back(r.graph.nodes[i].estimate);
    tracked.push_back(r.maps[i].world_T_map);
    truth_maps.push_back(sensor[static_cast<std::size_t>(r.first_revolution[i])]);
  }
  std::tie(t.rpe_m, t.rpe_rad) = LocalMapRpe(optimized, truth_maps);
  std::tie(t.tracking_rpe_m, t.tracking_rpe_rad) = LocalMapRpe(tracked, truth_maps);
  for (const auto& c : r.closures) {
    const Eigen::Isometry3d truth_T = truth_maps[static_cast<std::size_t>(c.candidate.reference)].inverse() *
                                      truth_maps[static_cast<std::size_t>(c.candidate.current)];
    const Eigen::Isometry3d error = truth_T.inverse() * c.validation.result.target_T_source;
    t.closure_errors.emplace_back(error.translation().norm(), Eigen::AngleAxisd(error.linear()).angle() * kRadToDeg);
  }
  t.revisits = static_cast<int>(revisits.revisit_pairs.size());
  t.informative_revisits = static_cast<int>(revisits.informative_pairs.size());
  // A kept closure is correct when its transform is within tolerance of the truth's (maps
  // that see one place from paths more than a lane apart count too); recall counts the
  // informative same-direction revisits with a correct closure.
  std::set<std::pair<int, int>> found;
  for (std::size_t i = 0; i < r.closures.size(); ++i) {
    const ClosureRecord& c = r.closures[i];
    if (!c.kept) continue;
    ++t.kept;
    if (t.closure_errors[i].first > options.tolerance_m || t.closure_errors[i].second > options.tolerance_deg) continue;
    ++t.correct;
    found.insert({c.candidate.reference, c.candidate.current});
  }
  for (const auto& pair : found) t.revisits_found += revisits.informative_pairs.count(pair) > 0 ? 1 : 0;
  return t;
}

const char* SourceName(const ClosureRecord& c) {
  if (c.edited) return "edit";
  if (c.injected) return "injected";
  return c.candidate.source == loops::CandidateSource::kDistance ? "distance" : "shape";
}

// With the truth, each line adds the registered transform's error against it.
void WriteClosures(const CatacombResult& r, const std::optional<ClosureTruth>& truth, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "# reference current source verdict inlier_share chi2_per_inlier dcs_scale"
      << (truth ? " truth_error_m truth_error_deg" : "") << " reason\n";
  for (std::size_t i = 0; i < r.closures.size(); ++i) {
    const ClosureRecord& c = r.closures[i];
    char line[256];
    std::snprintf(line, sizeof line, "%d %d %s %s %.4f %.4f %.4f", c.candidate.reference, c.candidate.current,
                  SourceName(c), c.kept ? "kept" : c.factor ? "dropped" : c.validation.accepted ? "accepted" : "rejected",
                  c.validation.inlier_share, c.validation.chi2_per_inlier, c.scale);
    out << line;
    if (truth) {
      std::snprintf(line, sizeof line, " %.3f %.3f", truth->closure_errors[i].first, truth->closure_errors[i].second);
      out << line;
    }
    out << (c.validation.reason.empty() ? "" : " " + c.validation.reason) << '\n';
  }
  if (!out) Fail(2, path.string() + ": write failed");
}

// The local maps' stored points at their optimized poses, streamed map by map: the whole
// map is never in memory.
void WriteMapCloud(const Args& a, const CatacombResult& r) {
  const loops::LocalMapStore store(a.options.out / "local_maps", a.options.store);
  auto writer = hal::cloud::PlyStreamWriter::Open(a.options.out / "map.ply", true);
  if (!writer.ok()) Fail(2, writer.error().message);
  for (std::size_t i = 0; i < r.maps.size(); ++i) {
    auto stored = store.ReadStored(static_cast<int>(i));
    if (!stored.ok()) Fail(2, stored.error().message);
    const Eigen::Matrix4f world_T_map = r.graph.nodes[i].estimate.matrix().cast<float>();
    if (Status s = writer->Append(stored->points, stored->normals, world_T_map); !s.ok()) Fail(2, s.error().message);
  }
  if (Status s = writer->Close(); !s.ok()) Fail(2, s.error().message);
}

void WriteTumOrFail(const std::vector<hal::trajectory::StampedPose>& poses, const std::filesystem::path& path) {
  if (poses.empty()) return;
  if (Status s = hal::trajectory::WriteTum(poses, path); !s.ok()) Fail(2, s.error().message);
}

// Writes every file; returns the prior map's viewpoints and the grid's seconds.
std::pair<std::size_t, double> WriteOutputs(const Args& a, const CatacombResult& r, const std::optional<ClosureTruth>& truth) {
  const std::filesystem::path& out = a.options.out;
  if (Status s = graph::WriteG2oSe3File(r.graph, (out / "graph.g2o").string()); !s.ok()) Fail(2, s.error().message);
  WriteTumOrFail(r.trajectory, out / "trajectory.tum");
  WriteTumOrFail(r.drive.trajectory, out / "tracking.tum");
  WriteTumOrFail(r.drive.odometry, out / "odometry.tum");
  WriteTumOrFail(r.drive.truth, out / "truth.tum");
  WriteClosures(r, truth, out / "closures.txt");
  WriteMapCloud(a, r);
  if (!a.options.drive.build_map) return {0, 0.0};
  const auto start = std::chrono::steady_clock::now();
  auto mosaic = GridCatacomb(a.options, r);
  if (!mosaic.ok()) Fail(2, mosaic.error().message);
  if (!*mosaic) Fail(3, a.options.drive.capture.string() + ": no revolution gridded at the optimized poses: nothing to map");
  const double grid_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto written = WriteTrajectoryMap(std::move(**mosaic), r.trajectory, out,
                                    "flat2d-map build --mode catacomb (flat2d " FLAT2D_VERSION ")",
                                    "drive " + a.options.drive.capture.string() + ", local-map 3D SLAM");
  if (!written.ok()) Fail(2, written.error().message);
  return {written->viewpoints, grid_seconds};
}

struct Counts {
  int distance = 0, shape = 0, injected = 0, accepted = 0, kept = 0, injected_accepted = 0, injected_kept = 0;
  int edits_added = 0, failure_cuts = 0;
};

Counts CountsOf(const CatacombResult& r) {
  Counts n;
  for (const auto& c : r.closures) {
    if (c.edited) {
      ++n.edits_added;
      continue;
    }
    if (c.injected) ++n.injected;
    else if (c.candidate.source == loops::CandidateSource::kDistance) ++n.distance;
    else ++n.shape;
    n.accepted += c.validation.accepted ? 1 : 0;
    n.kept += c.kept ? 1 : 0;
    n.injected_accepted += c.injected && c.validation.accepted ? 1 : 0;
    n.injected_kept += c.injected && c.kept ? 1 : 0;
  }
  for (std::size_t i = 0; i + 1 < r.maps.size(); ++i) {
    n.failure_cuts += r.last_revolution[i] < r.first_revolution[i + 1] ? 1 : 0;
  }
  return n;
}

void PrintText(const Args& a, const CatacombResult& r, const Counts& n) {
  std::printf("%d revolutions (%s) tracked into %zu local maps, %d failed registrations\n", r.drive.frames,
              r.drive.sensor.c_str(), r.maps.size(), r.drive.failures);
  std::printf("candidates: %d by distance, %d by trajectory shape, %d injected; %d accepted by NICP, %d kept by the "
              "graph (%d injected accepted, %d kept)\n",
              n.distance, n.shape, n.injected, n.accepted, n.kept, n.injected_accepted, n.injected_kept);
  std::printf("wrote %s: graph.g2o, trajectory.tum, tracking.tum, map.ply, closures.txt, local_maps/%s\n",
              a.options.out.c_str(), a.options.drive.build_map ? ", map.f2m, map.png" : "");
}

void PrintJson(const Args& a, const CatacombResult& r, const Counts& n, std::pair<std::size_t, double> map,
               const std::optional<ClosureTruth>& truth) {
  const auto frame = evaluation::PercentilesOf(r.drive.frame_ms);
  graph::Se3PoseGraph initial = r.graph;
  for (std::size_t i = 0; i < r.maps.size(); ++i) initial.nodes[i].estimate = r.maps[i].world_T_map;
  std::printf("{\"frames\": %d, \"failures\": %d, \"frame_ms_p50\": %.3f, \"frame_ms_p95\": %.3f, "
              "\"registration_ms_p50\": %.3f, \"sensor\": \"%s\", \"local_maps\": %zu, \"tracking_failures_cut\": %d, "
              "\"candidates\": %d, \"candidates_distance\": %d, \"candidates_shape\": %d, \"candidates_injected\": %d, "
              "\"validated\": %zu, \"accepted\": %d, \"closures_kept\": %d, \"injected_accepted\": %d, "
              "\"injected_kept\": %d, \"edits_added\": %d, \"edits_removed\": %zu, \"candidate_seconds\": %.3f, "
              "\"validation_ms_p50\": %.3f, \"solve_seconds\": %.4f, \"solve_rounds\": %d, \"graph_cost_initial\": %.6g, "
              "\"graph_cost_final\": %.6g, \"tracking_seconds\": %.3f, \"grid_seconds\": %.3f, \"viewpoints\": %zu",
              r.drive.frames, r.drive.failures, frame.p50, frame.p95, evaluation::PercentilesOf(r.drive.registration_ms).p50,
              r.drive.sensor.c_str(), r.maps.size(), n.failure_cuts, n.distance + n.shape + n.injected, n.distance,
              n.shape, n.injected, r.validation_ms.size(), n.accepted, n.kept, n.injected_accepted, n.injected_kept,
              n.edits_added, a.options.edits.removals.size(), r.candidate_seconds,
              evaluation::PercentilesOf(r.validation_ms).p50, r.solve.seconds, r.solve.rounds, graph::G2oChi2(initial),
              graph::G2oChi2(r.graph), r.tracking_seconds, map.second, map.first);
  std::printf(", \"tracked_distance_m\": %.3f", PathLength(r.trajectory));
  const auto discounted = std::count_if(r.failure_tie_scales.begin(), r.failure_tie_scales.end(),
                                        [&](double scale) { return scale < a.options.robust.min_kept_scale; });
  std::printf(", \"failure_ties\": %zu, \"failure_ties_overruled\": %td", r.failure_tie_scales.size(), discounted);
  const LocalMapCuts& cuts = r.drive.local_map_cuts;
  std::printf(", \"cuts_distance\": %d, \"cuts_angle\": %d, \"cuts_overlap\": %d, \"cuts_failure\": %d", cuts.distance,
              cuts.angle, cuts.overlap, cuts.failure);
  if (!a.drive.options.anchor.empty()) {
    const Drift d = DriftAgainst(a.drive.options.anchor, r.trajectory);
    std::printf(", \"distance_m\": %.3f, \"drift_percent\": %.4f, \"end_error_m\": %.4f, \"max_error_m\": %.4f", d.distance_m,
                d.percent(), d.end_error_m, d.max_error_m);
  }
  if (truth) {
    const double recall = truth->informative_revisits > 0
                              ? static_cast<double>(truth->revisits_found) / truth->informative_revisits
                              : 0.0;
    std::printf(", \"revisits\": %d, \"informative_revisits\": %d, \"closures_correct\": %d, \"closure_precision\": %.4f, "
                "\"closure_recall\": %.4f, \"local_map_rpe_mean_m\": %.5f, \"local_map_rpe_mean_rad\": %.6f, "
                "\"tracking_local_map_rpe_mean_m\": %.5f, \"tracking_local_map_rpe_mean_rad\": %.6f",
                truth->revisits, truth->informative_revisits, truth->correct,
                truth->kept > 0 ? static_cast<double>(truth->correct) / truth->kept : 0.0, recall,
                truth->rpe_m, truth->rpe_rad, truth->tracking_rpe_m, truth->tracking_rpe_rad);
  }
  std::printf("}\n");
}

}  // namespace

int CatacombCommand(int argc, char** argv) {
  Args a = ParseArgs(argc, argv);
  Prepare(a);
  std::optional<std::vector<hal::trajectory::StampedPose>> truth;
  if (a.truth) {
    auto read = hal::trajectory::ReadTum(*a.truth);
    if (!read.ok()) Fail(2, read.error().message);
    if (read->size() < 2) Fail(2, *a.truth + ": fewer than 2 poses");
    truth = std::move(*read);
  }
  auto built = BuildCatacomb(a.options);
  if (!built.ok()) Fail(2, built.error().message);
  const CatacombResult& r = *built;
  if (!truth && !r.drive.truth.empty()) truth = r.drive.truth;  // a KITTI sequence's poses.txt
  std::optional<ClosureTruth> judged;
  if (truth) judged = JudgeClosures(a, r, *truth);
  const auto map = WriteOutputs(a, r, judged);
  const Counts n = CountsOf(r);
  if (!a.drive.json) {
    PrintText(a, r, n);
    return 0;
  }
  PrintJson(a, r, n, map, judged);
  return 0;
}

}  // namespace flat2d::localization::tools
