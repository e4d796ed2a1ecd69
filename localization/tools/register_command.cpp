#include "localization/tools/register_command.hpp"

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/cloud/tum_depth_png.hpp"
#include "hal/trajectory/transform_file.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/registration/snicp.hpp"
#include "maps/range3d/range_frame.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kRegisterUsage = R"(
register: NICP (thesis 5.1) of SOURCE onto TARGET; prints target_T_source, the 4x4 with
p_target = T p_source (the lidar3d reference files' convention), H (the 6x6 information
over (dt, dq)), iterations, inliers and time. Files: .png TUM depth (metres = value/5000),
.pcd, .ply, .bin (KITTI). An organized target (depth image, Velodyne laser rows, KITTI
elevation bins) registers by projection into its image, an unorganized one by KD-tree.
  --init FILE           the initial guess, a 4x4 transform file (default identity)
  --method M            nicp (default), point-to-plane (Omega^n = 0, pairs by distance) or
                        snicp (depth PNGs: cross-product normals, 3 iterations at 1/4, 1/2, 1)
  --sensor S            auto (default), pinhole, vlp16, hdl32e, vlp32c, kitti64, unorganized
  --kdtree              KD-tree correspondences on (p, n/3) even for organized clouds
  --alpha A             KD-tree mode: the weight of normals against positions, metres
                        (default 1/3, Eq. 6.10; scale it with the scene)
  --iterations N        (default 10)
  --radius M[,M...]     the surface statistics radius R; several: coarse to fine, both
                        clouds refitted before each later R, the last taking 5 of the
                        iterations (default 0.1,0.03 depth images, 0.3,0.05 LiDAR, 0.1 PLY)
  --flat-curvature S    sigma below which a surface is a disc (Eq. 5.2; default 0.02)
  --curvature-floor S   Eq. 5.7 compares sigmas raised to at least S, so flat patches
                        always agree (default 0: the sigmas as fitted)
  --max-distance M      eps_d of Eq. 5.6 (default 0.5)
  --min-normal-dot C    eps_n of Eq. 5.8 (default 0.95)
  --acquire N           first N iterations of KD-tree pairs with the gates opened, flat
                        patches' sigmas raised to 0.02 (far guesses: projective pairs need
                        a near one); then the stages above (default 0: none; not in the
                        thesis)
  --acquire-gates D,C   eps_d and eps_n while acquiring (default 3,0.5)
  --image-scale N       depth images: every N-th pixel and row (default 1: all of them);
                        4 is 160x120, the working resolution of the NICP authors' Kinect
                        configuration (docs/benchmarks.md, "Working resolution")
  --snicp-scales S,S,...  snicp: the pyramid's levels, coarse to fine, as divisors of the
                        --image-scale resolution (default 4,2,1, thesis 5.3)
  --columns N           LiDAR range image columns (default 2160)
  --chi2-bound K        winsorization bound of Eq. 4.11 (default 10)
  --inverse-depth-weights  weigh each pair by 1 / (d_i d_j), the points' depths in their
                        own frames (Eq. 6.7: far points are noisier); projective mode only
  --damping L           lambda of Eq. 5.15 relative to H's mean diagonal (default 1e-4)
  --normal-weight W     scales Omega^n at R = 0.1 m, by (R/0.1)^2 at other R
                        (default 1, Eq. 5.14)
  --intrinsics FX,FY,CX,CY  depth camera (default 525,525,319.5,239.5)
  --viewpoint X,Y,Z     unorganized clouds: where the scanner was (default 0,0,0)
  --json                one JSON object: target_T_source, H, iterations, inliers,
                        correspondences, chi2, converged, failure, time_ms, ...
)";

namespace {

using registration::FrameRegistration;
constexpr std::string_view kTool = "flat2d-map";

struct RegisterArgs {
  std::string source, target;
  std::optional<std::string> init;
  registration::RegistrationMethod method = registration::RegistrationMethod::kNicp;
  registration::CorrespondenceMode mode = registration::CorrespondenceMode::kAuto;
  registration::NicpOptions nicp;
  registration::AcquisitionOptions acquisition;
  maps::range3d::RangeFrameOptions frames;
  std::optional<std::vector<float>> radii;  // --radius, coarse to fine; else per sensor
  bool snicp = false;
  registration::SnicpOptions snicp_options;
  bool json = false;
};

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

void SetRadius(RegisterArgs& a, float radius) {
  a.frames.depth_statistics.radius_m = radius;
  a.frames.lidar_statistics.radius_m = radius;
  a.frames.unorganized_statistics.radius_m = radius;
}

void SetRadii(RegisterArgs& a, const std::vector<double>& radii) {
  SetRadius(a, static_cast<float>(radii.front()));
  a.radii.emplace();
  for (const double radius : radii) a.radii->push_back(static_cast<float>(radius));
}

// --radius, or the defaults: coarse to fine on organized frames, one radius on
// unorganized clouds (the bunny's scans have their own scale).
std::vector<float> RadiiFor(const RegisterArgs& a, const maps::range3d::RangeFrame& target) {
  if (a.radii) return *a.radii;
  if (!target.organized()) return {target.statistics_radius_m};
  const bool depth = target.sensor == maps::range3d::SensorModel::kPinhole;
  return {target.statistics_radius_m, depth ? registration::kDepthFineRadiusM : registration::kLidarFineRadiusM};
}

void SetFlatCurvature(RegisterArgs& a, double value) {
  const auto sigma = static_cast<float>(value);
  a.frames.depth_statistics.flat_curvature = sigma;
  a.frames.lidar_statistics.flat_curvature = sigma;
  a.frames.unorganized_statistics.flat_curvature = sigma;
}

void SetAcquisitionGates(RegisterArgs& a, const std::vector<double>& gates) {
  if (!(gates[0] > 0.0) || !(gates[1] >= -1.0 && gates[1] <= 1.0)) {
    Fail(1, "register: --acquire-gates is D,C with D > 0 metres and C in [-1, 1]");
  }
  a.acquisition.max_distance_m = static_cast<float>(gates[0]);
  a.acquisition.min_normal_dot = static_cast<float>(gates[1]);
}

RegisterArgs ParseArgs(int argc, char** argv) {
  RegisterArgs a;
  int positional = 0;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto number = [&] { return maps::cli::ParseNumber(kTool, arg, value()); };
    auto number_in = [&](double low, double high) {
      return static_cast<float>(maps::cli::ParseNumberIn(kTool, arg, value(), low, high));
    };
    if (arg == "--init") a.init = value();
    else if (arg == "--method") {
      const std::string_view name = value();
      a.snicp = name == "snicp";
      const auto method = a.snicp ? registration::RegistrationMethod::kNicp : registration::ParseMethod(name);
      if (!method) Fail(1, "register: --method is nicp, snicp or point-to-plane");
      a.method = *method;
    } else if (arg == "--sensor") {
      const auto sensor = maps::range3d::ParseSensorModel(value());
      if (!sensor) Fail(1, "register: --sensor is auto, pinhole, vlp16, hdl32e, vlp32c, kitti64 or unorganized");
      a.frames.sensor = *sensor;
    } else if (arg == "--kdtree") a.mode = registration::CorrespondenceMode::kKdTree;
    else if (arg == "--alpha") a.nicp.kdtree_alpha = static_cast<float>(number());
    else if (arg == "--iterations") a.nicp.iterations = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, 1000));
    else if (arg == "--radius") SetRadii(a, maps::cli::ParseDecreasing(kTool, arg, value(), 1e-4, 100.0));
    else if (arg == "--flat-curvature") SetFlatCurvature(a, maps::cli::ParseNumberIn(kTool, arg, value(), 0.0, 1.0));
    else if (arg == "--curvature-floor") a.nicp.curvature_floor = number_in(0.0, 1.0);
    else if (arg == "--min-normal-dot") a.nicp.min_normal_dot = number_in(-1.0, 1.0);
    else if (arg == "--acquire") a.acquisition.iterations = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 1000));
    else if (arg == "--acquire-gates") SetAcquisitionGates(a, maps::cli::ParseNumberList(kTool, arg, value(), 2));
    else if (arg == "--max-distance") a.nicp.max_distance_m = static_cast<float>(number());
    else if (arg == "--chi2-bound") a.nicp.chi2_bound = number();
    else if (arg == "--image-scale") a.frames.image_scale = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, 8));
    else if (arg == "--columns") a.frames.lidar_columns = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 16, 32768));
    else if (arg == "--snicp-scales") a.snicp_options.scales = maps::cli::ParseCoarseToFine(kTool, arg, value(), 64);
    else if (arg == "--inverse-depth-weights") a.nicp.inverse_depth_weights = true;
    else if (arg == "--damping") a.nicp.damping = number();
    else if (arg == "--normal-weight") a.nicp.normal_weight = number();
    else if (arg == "--intrinsics") {
      const auto v = maps::cli::ParseNumberList(kTool, arg, value(), 4);
      a.frames.intrinsics = {640, 480, static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), static_cast<float>(v[3])};
    } else if (arg == "--viewpoint") {
      const auto v = maps::cli::ParseNumberList(kTool, arg, value(), 3);
      a.frames.viewpoint = Eigen::Vector3d(v[0], v[1], v[2]).cast<float>();
    } else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("-") && positional < 2) (positional++ == 0 ? a.source : a.target) = std::string(arg);
    else Fail(1, "register: unknown argument " + std::string(arg) + "\n" + kRegisterUsage);
  }
  if (positional != 2) Fail(1, std::string("register needs SOURCE and TARGET\n") + kRegisterUsage);
  if (a.snicp && a.acquisition.iterations > 0) Fail(1, "register: --acquire is for nicp and point-to-plane");
  return a;
}

struct LoadedFrame {
  maps::range3d::RangeFrame frame;
  double seconds = 0.0;  // read + statistics
};

LoadedFrame LoadOrFail(const std::string& path, const maps::range3d::RangeFrameOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto frame = maps::range3d::LoadRangeFrame(path, options);
  if (!frame.ok()) Fail(2, frame.error().message);
  return {std::move(*frame), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

std::string MatrixJson(const Eigen::MatrixXd& m) {
  std::string out = "[";
  for (Eigen::Index row = 0; row < m.rows(); ++row) {
    out += row ? ", [" : "[";
    for (Eigen::Index col = 0; col < m.cols(); ++col) {
      char number[32];
      std::snprintf(number, sizeof number, "%s%.9g", col ? ", " : "", m(row, col));
      out += number;
    }
    out += "]";
  }
  return out + "]";
}

void PrintJson(const FrameRegistration& r, const LoadedFrame& source, const LoadedFrame& target, const RegisterArgs& a) {
  std::printf("{\"target_T_source\": %s, \"H\": %s, \"iterations\": %d, \"inliers\": %d, \"correspondences\": %d, "
              "\"chi2\": %.9g, \"converged\": %s, \"failure\": \"%s\", \"method\": \"%s\", \"correspondence\": \"%s\", "
              "\"time_ms\": %.3f, \"source_load_ms\": %.3f, \"target_load_ms\": %.3f, \"source_sensor\": \"%s\", "
              "\"target_sensor\": \"%s\", \"source_points\": %zu, \"target_points\": %zu}\n",
              MatrixJson(r.result.target_T_source.matrix()).c_str(), MatrixJson(r.result.information).c_str(),
              r.result.iterations, r.result.inliers, r.result.correspondences, r.result.chi2,
              r.result.converged ? "true" : "false", registration::FailureName(r.result.failure),
              a.snicp ? "snicp" : std::string(registration::MethodName(a.method)).c_str(), r.kdtree ? "kdtree" : "projective",
              1e3 * r.seconds, 1e3 * source.seconds, 1e3 * target.seconds,
              std::string(maps::range3d::SensorModelName(source.frame.sensor)).c_str(),
              std::string(maps::range3d::SensorModelName(target.frame.sensor)).c_str(), source.frame.cloud.size(),
              target.frame.cloud.size());
}

void PrintText(const FrameRegistration& r, const LoadedFrame& source, const LoadedFrame& target) {
  std::printf("target_T_source:\n%s", hal::trajectory::FormatTransform(r.result.target_T_source).c_str());
  std::printf("H:\n");
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) std::printf("%s%.6g", col ? " " : "", r.result.information(row, col));
    std::printf("\n");
  }
  std::printf("iterations: %d%s\ninliers: %d of %d correspondences (%s)\nchi2: %.6g\n", r.result.iterations,
              r.result.converged ? " (converged)" : "", r.result.inliers, r.result.correspondences,
              r.kdtree ? "kd-tree" : "projective", r.result.chi2);
  std::printf("time: %.2f ms registration; %.2f / %.2f ms reading and statistics of source / target\n",
              1e3 * r.seconds, 1e3 * source.seconds, 1e3 * target.seconds);
  std::printf("clouds: source %zu points (%s), target %zu points (%s)\n", source.frame.cloud.size(),
              std::string(maps::range3d::SensorModelName(source.frame.sensor)).c_str(), target.frame.cloud.size(),
              std::string(maps::range3d::SensorModelName(target.frame.sensor)).c_str());
  if (!r.result.ok()) std::printf("failed: %s\n", registration::FailureName(r.result.failure));
}

}  // namespace

// SNICP: both files depth PNGs, their pyramids built while timed as "load".
FrameRegistration RegisterSnicpFiles(const RegisterArgs& a, const Eigen::Isometry3d& guess, LoadedFrame& source,
                                     LoadedFrame& target) {
  registration::SnicpFrame pyramids[2];
  LoadedFrame* loaded[2] = {&source, &target};
  const std::string* paths[2] = {&a.source, &a.target};
  for (int k = 0; k < 2; ++k) {
    const auto start = std::chrono::steady_clock::now();
    auto depth = hal::cloud::ReadTumDepthPng(*paths[k], a.frames.depth_scale);
    if (!depth.ok()) Fail(2, depth.error().message + " (snicp registers depth images)");
    pyramids[k] = registration::MakeSnicpFrame(*depth, a.frames, a.snicp_options);
    loaded[k]->frame = pyramids[k].levels.back();
    loaded[k]->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return registration::RegisterSnicp(pyramids[1], pyramids[0], guess, a.nicp, a.snicp_options);
}

int RegisterCommand(int argc, char** argv) {
  const RegisterArgs a = ParseArgs(argc, argv);
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  if (a.init) {
    auto init = hal::trajectory::ReadTransformFile(*a.init);
    if (!init.ok()) Fail(2, init.error().message);
    guess = *init;
  }
  LoadedFrame source, target;
  FrameRegistration r;
  if (a.snicp) {
    r = RegisterSnicpFiles(a, guess, source, target);
  } else {
    source = LoadOrFail(a.source, a.frames);
    target = LoadOrFail(a.target, a.frames);
    r = registration::RegisterFramesOverRadii(a.frames, RadiiFor(a, target.frame), target.frame, source.frame, guess,
                                              a.method, a.nicp, a.mode, a.acquisition);
  }
  if (a.json) PrintJson(r, source, target, a);
  else PrintText(r, source, target);
  return r.result.ok() ? 0 : 3;
}

}  // namespace flat2d::localization::tools
