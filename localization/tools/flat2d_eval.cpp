// flat2d-eval: estimates against references.
//   grid       structure precision and recall of a class grid against a truth grid (issue 6)
//   relations  the relations metric of the 2D SLAM benchmarks (Kuemmerle et al. 2009)
//   traj       absolute trajectory error after rigid alignment; with --3d the TUM RGB-D
//              benchmark's ATE and RPE of full 3D poses
//   loops      loop-closure candidates on a drifted truth trajectory (issue 12; loops_command.hpp)
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read or is invalid.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "localization/evaluation/relations.hpp"
#include "localization/evaluation/trajectory_error.hpp"
#include "localization/evaluation/trajectory_error_3d.hpp"
#include "localization/evaluation/trajectory_file.hpp"
#include "localization/tools/loops_command.hpp"
#include "localization/tools/trajectory_plots.hpp"
#include "maps/grid/class_grid_file.hpp"
#include "maps/grid/structure_comparison.hpp"
#include "maps/render/png_writer.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-eval";

constexpr const char* kUsage = R"(usage:
  flat2d-eval grid --truth A.yaml --grid B.yaml [--tolerance CELLS] [--observed-radius CELLS] [--json]
  flat2d-eval relations --trajectory EST.tum (--relations FILE | --reference REF.tum) [options] [--json]
  flat2d-eval traj --truth T.tum --est E.tum [--align] [--max-gap S] [--json]
                   [--plot STEM [--map MAP.yaml] [--odometry O.tum]]
  flat2d-eval traj --truth T.tum --est E.tum --3d [--delta S] [--max-gap S] [--json]

grid: slammable cells of grid B against the occupied (slammable) cells of truth A, both
map_server YAML + PGM files in one world frame (flat2d-sim's truth_map.yaml, flat2d-grid's
--out). precision: share of B's slammable cells within --tolerance truth cells (Chebyshev)
of true structure. recall: share of the truth's structure faces that B observed near (any
class within --observed-radius cells of the point that many + 1 cells in front of the
face) and found within --tolerance.
  --tolerance CELLS        default 1
  --observed-radius CELLS  default 2 (10 cm at 5 cm)
  --json                   one JSON object: precision, recall and the counts behind them

relations: for each relation (t1, t2, d*), the estimate's d = x(t1)^-1 x(t2) and the error
d*^-1 d; mean and standard deviation of |e_t| (m), |e_theta| (deg) and their squares, the
four rows of the published tables. Relations come from a Freiburg .relations file ("t1 t2
x y z roll pitch yaw") or are drawn from a reference trajectory: each pose with the next
one --min-step metres further on, and each revisit (an earlier pose within --loop-radius
after at least --loop-min-path metres of travel).
  --relations FILE         Freiburg .relations file
  --reference REF.tum      draw the relations from this trajectory instead
  --write-relations FILE   write the relations used, in the Freiburg format
  --min-step M             default 0.5
  --loop-radius M          default 2
  --loop-min-path M        default 10
  --max-gap S              the estimate's poses around a relation's time at most S apart (default 1)

traj: the estimate sampled at the truth's times, position RMSE, mean, median and max (m)
and heading RMSE (deg), in the frames as given (a map georeferenced to the truth's frame);
percentiles (50, 95, 99) of the position error and of its longitudinal and lateral parts
(along and across the truth's heading); the heading error's share within 0.02 and
0.025 rad, its worst and its histogram in 0.005 rad bins.
  --align                  after the best rigid 2D alignment (Horn), for an estimate in
                           another frame (raw odometry, a map not anchored to the truth)
  --plot STEM              write STEM_heading.png (the heading error's histogram: a bar per
                           0.005 rad bin, full height 100 %, the 0.02 and 0.025 rad edges in
                           red and orange, everything beyond 0.1 rad in the grey last bar) and
                           STEM_trajectory.png (truth green, estimate blue, in the truth's
                           frame)
  --map MAP.yaml           ... the trajectories over this class grid (flat2d-map render)
  --odometry O.tum         ... and this open-loop odometry in red (flat2d-localize
                           --odometry-out), as given
  --max-gap S              the estimate's poses around a truth time at most S apart (default 1)
  --trajectory, --reference  the same as --est, --truth

traj --3d: full 3D poses in the TUM RGB-D benchmark's conventions (Sturm et al., IROS 2012;
its evaluate_ate.py and evaluate_rpe.py). The truth is interpolated at each estimate pose's
time (position linearly, rotation by slerp) between its two poses around that time when
they are at most --max-gap apart; the benchmark takes the nearest truth pose within 0.02 s
instead, which at its 100 Hz truth leaves up to 5 ms of time offset. ATE: RMSE, mean,
median and max (m) of the position error after the best rigid SE(3) alignment (Horn /
Umeyama, no scale). RPE: E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j), truth Q and estimate P, RMSE and
median of |translation| and of the rotation angle, over consecutive estimate poses (m and deg
per frame) and over pairs with t_j the first estimate time >= t_i + --delta (m and deg over
the interval). Estimate poses the truth does not cover are left out.
  --delta S                the RPE interval (default 1)
  --max-gap S              the truth's poses around an estimate time at most S apart (default
                           0.02, the benchmark's association limit; the truth of TUM fr1 is
                           100 Hz)
  --json                   one JSON object: ate_rmse_m, ate_mean_m, ate_median_m, ate_max_m,
                           rpe_frame_trans_rmse_m, rpe_frame_rot_rmse_deg,
                           rpe_frame_trans_median_m, rpe_frame_rot_median_deg, rpe_delta_s,
                           rpe_delta_trans_rmse_m, rpe_delta_rot_rmse_deg,
                           rpe_delta_trans_median_m, rpe_delta_rot_median_deg, poses_matched,
                           pairs_frame, pairs_delta
  --align is implied; --plot, --map and --odometry are for the planar evaluation only.
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

int EvalGrid(int argc, char** argv) {
  std::string truth_path, grid_path;
  maps::StructureComparisonOptions options;
  bool json = false;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--truth") truth_path = value();
    else if (arg == "--grid") grid_path = value();
    else if (arg == "--tolerance") {
      options.tolerance_cells = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 1000));
    } else if (arg == "--observed-radius") {
      options.observed_radius_cells = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 100000));
    } else if (arg == "--json") json = true;
    else Fail(1, "unknown argument " + std::string(arg) + "\n" + kUsage);
  }
  if (truth_path.empty() || grid_path.empty()) Fail(1, std::string("grid needs --truth and --grid\n") + kUsage);
  auto truth = maps::ReadClassGrid(truth_path);
  if (!truth.ok()) Fail(2, truth.error().message);
  auto grid = maps::ReadClassGrid(grid_path);
  if (!grid.ok()) Fail(2, grid.error().message);

  const maps::StructureComparison c = maps::CompareStructure(*grid, *truth, options);
  if (json) {
    std::printf("{\"precision\":%.6f,\"recall\":%.6f,\"tolerance_cells\":%d,\"observed_radius_cells\":%d,"
                "\"grid_structure\":%zu,\"grid_matched\":%zu,\"grid_outside\":%zu,"
                "\"truth_faces\":%zu,\"truth_matched\":%zu}\n",
                c.precision(), c.recall(), options.tolerance_cells, options.observed_radius_cells,
                c.grid_structure, c.grid_matched, c.grid_outside, c.truth_faces, c.truth_matched);
  } else {
    std::printf("precision: %.4f (%zu of %zu slammable cells within %d cells of true structure)\n",
                c.precision(), c.grid_matched, c.grid_structure, options.tolerance_cells);
    std::printf("recall:    %.4f (%zu of %zu observed true structure faces found)\n", c.recall(),
                c.truth_matched, c.truth_faces);
    if (c.grid_outside > 0) std::printf("outside:   %zu slammable cells beyond the truth's extent\n", c.grid_outside);
  }
  return 0;
}

using localization::evaluation::TimedPose;

std::vector<TimedPose> ReadTrajectoryOrFail(const std::string& path) {
  auto trajectory = localization::evaluation::ReadTrajectory(path);
  if (!trajectory.ok()) Fail(2, trajectory.error().message);
  return std::move(*trajectory);
}

void PrintMeanStd(const char* name, const localization::evaluation::MeanStd& v, const char* unit) {
  std::printf("%-26s %.4f +/- %.4f %s\n", name, v.mean, v.std, unit);
}

int EvalRelations(int argc, char** argv) {
  std::string trajectory_path, relations_path, reference_path, write_path;
  localization::evaluation::RelationSampling sampling;
  double max_gap = 1.0;
  bool json = false;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    if (arg == "--trajectory") trajectory_path = value();
    else if (arg == "--relations") relations_path = value();
    else if (arg == "--reference") reference_path = value();
    else if (arg == "--write-relations") write_path = value();
    else if (arg == "--min-step") sampling.min_step_m = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--loop-radius") sampling.loop_radius_m = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--loop-min-path") sampling.loop_min_path_m = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--max-gap") max_gap = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--json") json = true;
    else Fail(1, "relations: unknown argument " + std::string(arg) + "\n" + kUsage);
  }
  if (trajectory_path.empty() || relations_path.empty() == reference_path.empty()) {
    Fail(1, std::string("relations needs --trajectory and one of --relations, --reference\n") + kUsage);
  }
  const std::vector<TimedPose> estimate = ReadTrajectoryOrFail(trajectory_path);
  std::vector<localization::evaluation::Relation> relations;
  if (!relations_path.empty()) {
    auto read = localization::evaluation::ReadRelations(relations_path);
    if (!read.ok()) Fail(2, read.error().message);
    relations = std::move(*read);
  } else {
    relations = localization::evaluation::MakeRelations(ReadTrajectoryOrFail(reference_path), sampling);
  }
  if (!write_path.empty()) {
    if (Status s = localization::evaluation::WriteRelations(relations, write_path); !s.ok()) Fail(2, s.error().message);
  }
  const auto e = localization::evaluation::EvaluateRelations(estimate, relations, max_gap);
  if (e.relations == 0) Fail(2, "no relation falls within the trajectory's time (" + std::to_string(e.unmatched) + " outside)");
  if (json) {
    std::printf("{\"relations\":%zu,\"unmatched\":%zu,\"translation_mean_m\":%.6f,\"translation_std_m\":%.6f,"
                "\"translation_sq_mean_m2\":%.6f,\"translation_sq_std_m2\":%.6f,\"rotation_mean_deg\":%.6f,"
                "\"rotation_std_deg\":%.6f,\"rotation_sq_mean_deg2\":%.6f,\"rotation_sq_std_deg2\":%.6f}\n",
                e.relations, e.unmatched, e.translation_m.mean, e.translation_m.std, e.translation_sq_m2.mean,
                e.translation_sq_m2.std, e.rotation_deg.mean, e.rotation_deg.std, e.rotation_sq_deg2.mean,
                e.rotation_sq_deg2.std);
  } else {
    std::printf("relations: %zu scored, %zu outside the trajectory\n", e.relations, e.unmatched);
    PrintMeanStd("abs. translational", e.translation_m, "m");
    PrintMeanStd("sq. translational", e.translation_sq_m2, "m^2");
    PrintMeanStd("abs. rotational", e.rotation_deg, "deg");
    PrintMeanStd("sq. rotational", e.rotation_sq_deg2, "deg^2");
  }
  return 0;
}

std::string PercentilesJson(const std::string& name, const localization::evaluation::ErrorPercentiles& p) {
  char text[160];
  std::snprintf(text, sizeof text, "\"%s_p50_m\":%.6f,\"%s_p95_m\":%.6f,\"%s_p99_m\":%.6f", name.c_str(), p.p50,
                name.c_str(), p.p95, name.c_str(), p.p99);
  return text;
}

std::string HistogramJson(const localization::evaluation::TrajectoryError& e) {
  std::string text;
  // Appended in two steps: GCC 12 flags `"," + std::to_string(...)` with a false -Wrestrict
  // once inlined into main.
  for (const std::size_t count : e.heading_histogram) {
    if (!text.empty()) text += ',';
    text += std::to_string(count);
  }
  return text;
}

void WritePngOrFail(const maps::RgbImage& image, const std::string& path) {
  if (Status written = maps::WritePng(image, path); !written.ok()) Fail(2, written.error().message);
}

// The --plot pictures; the estimate moved into the truth's frame when aligned.
void WriteTrajectoryPlots(const std::string& stem, const localization::evaluation::TrajectoryError& e,
                          const std::vector<localization::evaluation::TimedPose>& truth,
                          std::vector<localization::evaluation::TimedPose> estimate,
                          const std::optional<std::string>& map_path, const std::optional<std::string>& odometry_path) {
  WritePngOrFail(localization::PlotHeadingHistogram(e), stem + "_heading.png");
  for (auto& p : estimate) p.pose = e.reference_T_estimate * p.pose;
  std::optional<maps::ClassGrid> map;
  if (map_path) {
    auto read = maps::ReadClassGrid(*map_path);
    if (!read.ok()) Fail(2, read.error().message);
    map = std::move(*read);
  }
  std::vector<localization::evaluation::TimedPose> odometry;
  if (odometry_path) odometry = ReadTrajectoryOrFail(*odometry_path);
  localization::TrajectoryPlot plot;
  plot.truth = &truth;
  plot.estimate = &estimate;
  plot.odometry = odometry_path ? &odometry : nullptr;
  plot.map = map ? &*map : nullptr;
  WritePngOrFail(localization::PlotTrajectories(plot), stem + "_trajectory.png");
}

struct TrajArgs {
  std::string trajectory_path, reference_path;
  std::optional<std::string> plot_stem, map_path, odometry_path;
  std::optional<bool> align;
  std::optional<double> max_gap_s, delta_s;
  bool three_d = false;
  bool json = false;
};

TrajArgs ParseTrajArgs(int argc, char** argv) {
  TrajArgs a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    if (arg == "--est" || arg == "--trajectory") a.trajectory_path = value();
    else if (arg == "--truth" || arg == "--reference") a.reference_path = value();
    else if (arg == "--align") a.align = true;
    else if (arg == "--no-align") a.align = false;
    else if (arg == "--max-gap") a.max_gap_s = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--3d") a.three_d = true;
    else if (arg == "--delta") a.delta_s = maps::cli::ParseNumber(kTool, arg, value());
    else if (arg == "--json") a.json = true;
    else if (arg == "--plot") a.plot_stem = value();
    else if (arg == "--map") a.map_path = value();
    else if (arg == "--odometry") a.odometry_path = value();
    else Fail(1, "traj: unknown argument " + std::string(arg) + "\n" + kUsage);
  }
  if (a.trajectory_path.empty() || a.reference_path.empty()) {
    Fail(1, std::string("traj needs --truth and --est\n") + kUsage);
  }
  if ((a.map_path || a.odometry_path) && !a.plot_stem) Fail(1, "traj: --map and --odometry go with --plot");
  return a;
}

int EvalTraj2d(const TrajArgs& a) {
  const bool align = a.align.value_or(false);
  const auto estimate = ReadTrajectoryOrFail(a.trajectory_path);
  const auto truth = ReadTrajectoryOrFail(a.reference_path);
  const auto e = localization::evaluation::EvaluateTrajectory(estimate, truth, align, a.max_gap_s.value_or(1.0));
  if (e.poses == 0) Fail(2, "the estimate covers none of the truth's times");
  if (a.plot_stem) WriteTrajectoryPlots(*a.plot_stem, e, truth, estimate, a.map_path, a.odometry_path);
  if (a.json) {
    std::printf("{\"poses\":%zu,\"unmatched\":%zu,\"ate_rmse_m\":%.6f,\"ate_mean_m\":%.6f,\"ate_median_m\":%.6f,"
                "\"ate_max_m\":%.6f,\"rotation_rmse_deg\":%.6f,\"aligned\":%s,%s,%s,%s,"
                "\"heading_within_0_02\":%.6f,\"heading_within_0_025\":%.6f,\"heading_worst_rad\":%.6f,"
                "\"heading_histogram_bin_rad\":%.3f,\"heading_histogram\":[%s]}\n",
                e.poses, e.unmatched, e.rmse_m, e.mean_m, e.median_m, e.max_m, e.rotation_rmse_deg,
                align ? "true" : "false", PercentilesJson("position", e.position_m).c_str(),
                PercentilesJson("longitudinal", e.longitudinal_m).c_str(),
                PercentilesJson("lateral", e.lateral_m).c_str(), e.heading_within_0_02, e.heading_within_0_025,
                e.heading_worst_rad, localization::evaluation::kHeadingBinRad, HistogramJson(e).c_str());
  } else {
    std::printf("poses: %zu compared, %zu outside the estimate; %s\n", e.poses, e.unmatched,
                align ? "rigidly aligned" : "frames as given");
    std::printf("ATE: rmse %.4f m, mean %.4f m, median %.4f m, max %.4f m; heading rmse %.3f deg\n", e.rmse_m,
                e.mean_m, e.median_m, e.max_m, e.rotation_rmse_deg);
    const auto row = [](const char* name, const localization::evaluation::ErrorPercentiles& p) {
      std::printf("%-13s p50 %.4f m, p95 %.4f m, p99 %.4f m\n", name, p.p50, p.p95, p.p99);
    };
    row("position:", e.position_m);
    row("longitudinal:", e.longitudinal_m);
    row("lateral:", e.lateral_m);
    std::printf("heading: %.2f %% within 0.02 rad, %.2f %% within 0.025 rad, worst %.4f rad\n",
                100.0 * e.heading_within_0_02, 100.0 * e.heading_within_0_025, e.heading_worst_rad);
  }
  return 0;
}

std::vector<hal::trajectory::StampedPose> ReadTumOrFail(const std::string& path) {
  auto poses = hal::trajectory::ReadTum(path);
  if (!poses.ok()) Fail(2, poses.error().message);
  return std::move(*poses);
}

double PositiveSecondsOrFail(const char* flag, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    Fail(1, std::string("traj: ") + flag + " must be a positive number of seconds");
  }
  return value;
}

void PrintRelative3d(const std::string& name, const localization::evaluation::RelativeError3d& r) {
  std::printf("RPE %s (%zu pairs): translation rmse %.6f m, median %.6f m; rotation rmse %.4f deg, median %.4f deg\n",
              name.c_str(), r.pairs, r.trans_rmse_m, r.trans_median_m, r.rot_rmse_deg, r.rot_median_deg);
}

int EvalTraj3d(const TrajArgs& a) {
  if (a.plot_stem) Fail(1, "traj: --plot, --map and --odometry are for the planar evaluation, not --3d");
  if (a.align.has_value() && !*a.align) Fail(1, "traj: --3d always aligns (SE(3)); drop --no-align");
  localization::evaluation::TrajectoryError3dOptions options;
  if (a.max_gap_s) options.max_gap_s = PositiveSecondsOrFail("--max-gap", *a.max_gap_s);
  if (a.delta_s) options.rpe_delta_s = PositiveSecondsOrFail("--delta", *a.delta_s);
  const auto estimate = ReadTumOrFail(a.trajectory_path);
  const auto truth = ReadTumOrFail(a.reference_path);
  const auto result = localization::evaluation::EvaluateTrajectory3d(estimate, truth, options);
  if (!result.ok()) Fail(2, result.error().message);
  const localization::evaluation::TrajectoryError3d& e = *result;
  if (a.json) {
    std::printf("{\"ate_rmse_m\":%.6f,\"ate_mean_m\":%.6f,\"ate_median_m\":%.6f,\"ate_max_m\":%.6f,"
                "\"rpe_frame_trans_rmse_m\":%.6f,\"rpe_frame_rot_rmse_deg\":%.6f,"
                "\"rpe_frame_trans_median_m\":%.6f,\"rpe_frame_rot_median_deg\":%.6f,\"rpe_delta_s\":%.6f,"
                "\"rpe_delta_trans_rmse_m\":%.6f,\"rpe_delta_rot_rmse_deg\":%.6f,"
                "\"rpe_delta_trans_median_m\":%.6f,\"rpe_delta_rot_median_deg\":%.6f,"
                "\"poses_matched\":%zu,\"pairs_frame\":%zu,\"pairs_delta\":%zu}\n",
                e.ate_rmse_m, e.ate_mean_m, e.ate_median_m, e.ate_max_m, e.rpe_frame.trans_rmse_m,
                e.rpe_frame.rot_rmse_deg, e.rpe_frame.trans_median_m, e.rpe_frame.rot_median_deg, e.rpe_delta_s,
                e.rpe_delta.trans_rmse_m, e.rpe_delta.rot_rmse_deg, e.rpe_delta.trans_median_m,
                e.rpe_delta.rot_median_deg, e.poses_matched, e.rpe_frame.pairs, e.rpe_delta.pairs);
  } else {
    std::printf("poses: %zu matched, %zu outside the truth (interpolated, neighbours at most %.3f s apart)\n",
                e.poses_matched, e.poses_unmatched, options.max_gap_s);
    std::printf("ATE (SE(3)-aligned): rmse %.6f m, mean %.6f m, median %.6f m, max %.6f m\n", e.ate_rmse_m,
                e.ate_mean_m, e.ate_median_m, e.ate_max_m);
    PrintRelative3d("per frame", e.rpe_frame);
    char over[48];
    std::snprintf(over, sizeof over, "over %g s", e.rpe_delta_s);
    PrintRelative3d(over, e.rpe_delta);
  }
  return 0;
}

int EvalTraj(int argc, char** argv) {
  const TrajArgs args = ParseTrajArgs(argc, argv);
  if (!args.three_d && args.delta_s) Fail(1, "traj: --delta goes with --3d");
  return args.three_d ? EvalTraj3d(args) : EvalTraj2d(args);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string_view(argv[1]) == "relations") return EvalRelations(argc - 2, argv + 2);
  if (argc >= 2 && std::string_view(argv[1]) == "traj") return EvalTraj(argc - 2, argv + 2);
  if (argc >= 2 && std::string_view(argv[1]) == "grid") return EvalGrid(argc - 2, argv + 2);
  if (argc >= 2 && std::string_view(argv[1]) == "loops") return localization::tools::LoopsCommand(argc - 2, argv + 2);
  if (argc >= 2 && (std::string_view(argv[1]) == "--help" || std::string_view(argv[1]) == "-h")) {
    std::cout << kUsage << '\n' << localization::tools::kLoopsUsage;
    return 0;
  }
  Fail(1, std::string("unknown or missing command\n") + kUsage + "\n" + localization::tools::kLoopsUsage);
}
