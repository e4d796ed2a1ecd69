// flat2d-peer-register: SOURCE registered onto TARGET by PCL or Open3D, the peers that
// flat2d-map register (NICP) is compared with, from the same files and guess, on one thread
// (peer_registration.hpp says how). Prints target_T_source and the figures; --json one
// object with flat2d-map register's keys where they mean the same.
// Exit status: 0 ok, 1 usage, 2 a file cannot be read, 3 the library refused the input.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "hal/trajectory/transform_file.hpp"
#include "localization/peers/peer_registration.hpp"
#include "localization/peers/span_timer.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;
using localization::peers::PeerResult;

constexpr std::string_view kTool = "flat2d-peer-register";

constexpr const char* kUsage = R"(usage:
  flat2d-peer-register SOURCE TARGET --method M [options]

Registers SOURCE onto TARGET with another library and prints target_T_source, the 4x4 with
p_target = T p_source (flat2d-map register's convention), on one thread (OpenMP limited to
1). Files as flat2d-map register reads them: .pcd, .ply, .bin (KITTI), .png TUM depth
(metres = value/5000); NaN and zero-range points are dropped.
  --method M            pcl-gicp            pcl::GeneralizedIterativeClosestPoint (covariances
                                            from the k nearest; stops on steps below
                                            1e-4 m and 1e-4 rad, as pcl-point-to-plane)
                        pcl-point-to-plane  pcl::IterativeClosestPointWithNormals (target
                                            normals by pcl::NormalEstimation; stops on steps
                                            below 1e-4 m and 1e-4 rad)
                        o3d-point-to-plane  Open3D RegistrationICP, TransformationEstimation-
                                            PointToPlane (target normals by EstimateNormals)
                        o3d-gicp            Open3D RegistrationGeneralizedICP (covariances
                                            from both clouds' normals)
                        (Open3D stops on its defaults: fitness and RMSE changing below 1e-6)
  --init FILE           the initial guess, a 4x4 transform file (default identity)
  --max-distance M      max correspondence distance (default 0.5, as flat2d-map register)
  --iterations N        outer iterations at most (default 30, Open3D's default; PCL's own
                        are 10 for ICP and 200 for GICP)
  --voxel V             voxel-downsample both clouds first (PCL VoxelGrid, Open3D
                        VoxelDownSample), metres (default 0: every point)
  --neighbours K        k nearest points of a normal or covariance (default 20)
  --normal-radius R     normals from the points within R instead (default 0: k nearest;
                        PCL takes all of them, Open3D's hybrid search at most K; PCL's GICP
                        covariances stay k nearest)
  --intrinsics FX,FY,CX,CY  depth camera (default 525,525,319.5,239.5)
  --max-depth M         depth images: drop pixels deeper than M (default 8)
  --json                one JSON object: target_T_source, iterations (-1: not reported),
                        converged (null: not reported), inliers (source points within
                        --max-distance of the target at the result), inlier_rmse, time_ms
                        (the registration call), cpu_ms (the same in process CPU time),
                        prepare_ms (downsampling, normals, covariances), method,
                        source_points and target_points (as registered), ...
Exit status: 0 ok, 1 usage, 2 a file cannot be read, 3 the library refused the input.
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::string source, target;
  std::optional<std::string> init;
  std::optional<localization::peers::PeerMethod> method;
  localization::peers::PeerOptions options;
  localization::peers::PeerCloudOptions clouds;
  bool json = false;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  int positional = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto positive = [&] {
      const double v = maps::cli::ParseNumber(kTool, arg, value());
      if (!(v > 0.0)) Fail(1, std::string(arg) + " must be positive");
      return v;
    };
    auto non_negative = [&] {
      const double v = maps::cli::ParseNumber(kTool, arg, value());
      if (!(v >= 0.0)) Fail(1, std::string(arg) + " must not be negative");
      return v;
    };
    auto integer = [&](std::int64_t min) {
      return static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), min, 1000));
    };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--method") {
      a.method = localization::peers::ParsePeerMethod(value());
      if (!a.method) Fail(1, "--method is pcl-gicp, pcl-point-to-plane, o3d-point-to-plane or o3d-gicp");
    } else if (arg == "--init") a.init = value();
    else if (arg == "--max-distance") a.options.max_distance_m = positive();
    else if (arg == "--iterations") a.options.iterations = integer(1);
    else if (arg == "--voxel") a.options.voxel_m = non_negative();
    else if (arg == "--neighbours") a.options.neighbours = integer(3);
    else if (arg == "--normal-radius") a.options.normal_radius_m = non_negative();
    else if (arg == "--max-depth") a.clouds.max_depth_m = positive();
    else if (arg == "--intrinsics") {
      const auto v = maps::cli::ParseNumberList(kTool, arg, value(), 4);
      if (!(v[0] > 0.0 && v[1] > 0.0)) Fail(1, "--intrinsics: FX and FY must be positive");
      a.clouds.intrinsics = {v[0], v[1], v[2], v[3]};
    } else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("-") && positional < 2) (positional++ == 0 ? a.source : a.target) = std::string(arg);
    else Fail(1, "unknown argument " + std::string(arg) + " (see --help)");
  }
  if (positional != 2) Fail(1, "needs SOURCE and TARGET (see --help)");
  if (!a.method) Fail(1, "needs --method (see --help)");
  a.options.method = *a.method;
  return a;
}

struct Loaded {
  localization::peers::Points points;
  double ms = 0.0;
};

Loaded LoadOrFail(const std::string& path, const localization::peers::PeerCloudOptions& options) {
  const localization::peers::SpanTimer timer;
  auto points = localization::peers::LoadPeerPoints(path, options);
  if (!points.ok()) Fail(2, points.error().message);
  return {std::move(*points), timer.WallMs()};
}

std::string MatrixJson(const Eigen::Matrix4d& m) {
  std::string out = "[";
  for (int row = 0; row < 4; ++row) {
    out += row ? ", [" : "[";
    for (int col = 0; col < 4; ++col) {
      char number[32];
      std::snprintf(number, sizeof number, "%s%.9g", col ? ", " : "", m(row, col));
      out += number;
    }
    out += "]";
  }
  return out + "]";
}

const char* ConvergedJson(const PeerResult& r) { return !r.converged ? "null" : *r.converged ? "true" : "false"; }

void PrintJson(const PeerResult& r, const Args& a, const Loaded& source, const Loaded& target) {
  std::printf("{\"target_T_source\": %s, \"iterations\": %d, \"converged\": %s, \"inliers\": %d, "
              "\"inlier_rmse\": %.9g, \"method\": \"%s\", \"time_ms\": %.3f, \"cpu_ms\": %.3f, "
              "\"prepare_ms\": %.3f, \"source_load_ms\": %.3f, \"target_load_ms\": %.3f, \"source_points\": %zu, "
              "\"target_points\": %zu, \"source_points_read\": %zu, \"target_points_read\": %zu, "
              "\"max_distance\": %.9g, \"voxel\": %.9g}\n",
              MatrixJson(r.target_T_source.matrix()).c_str(), r.iterations, ConvergedJson(r), r.inliers,
              r.inlier_rmse_m, std::string(localization::peers::PeerMethodName(a.options.method)).c_str(), r.time_ms,
              r.cpu_ms, r.prepare_ms, source.ms, target.ms, r.source_points, r.target_points, source.points.size(),
              target.points.size(), a.options.max_distance_m, a.options.voxel_m);
}

void PrintText(const PeerResult& r, const Args& a, const Loaded& source, const Loaded& target) {
  std::printf("target_T_source:\n%s", hal::trajectory::FormatTransform(r.target_T_source).c_str());
  std::printf("method: %s\n", std::string(localization::peers::PeerMethodName(a.options.method)).c_str());
  if (r.iterations >= 0) std::printf("iterations: %d\n", r.iterations);
  else std::printf("iterations: not reported\n");
  std::printf("converged: %s\n", !r.converged ? "not reported" : *r.converged ? "yes" : "no (iteration limit)");
  std::printf("inliers: %d of %zu source points within %.3g m (RMSE %.4f m)\n", r.inliers, r.source_points,
              a.options.max_distance_m, r.inlier_rmse_m);
  std::printf("time: %.2f ms registration (%.2f ms CPU); %.2f ms preparation; %.2f / %.2f ms reading source / target\n",
              r.time_ms, r.cpu_ms, r.prepare_ms, source.ms, target.ms);
  std::printf("clouds: source %zu points registered of %zu read, target %zu of %zu\n", r.source_points,
              source.points.size(), r.target_points, target.points.size());
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = ParseArgs(argc, argv);
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  if (a.init) {
    auto init = hal::trajectory::ReadTransformFile(*a.init);
    if (!init.ok()) Fail(2, init.error().message);
    guess = *init;
  }
  const Loaded source = LoadOrFail(a.source, a.clouds);
  const Loaded target = LoadOrFail(a.target, a.clouds);
  localization::peers::UseOneThreadAndQuietLogs();
  auto result = localization::peers::RegisterPeer(target.points, source.points, guess, a.options);
  if (!result.ok()) Fail(3, result.error().message);
  if (a.json) PrintJson(*result, a, source, target);
  else PrintText(*result, a, source, target);
  return 0;
}
