#include "localization/tools/nicp_build_command.hpp"

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "localization/evaluation/trajectory_error.hpp"
#include "localization/tools/nicp_build.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::localization::tools {

const char* const kNicpBuildUsage = R"(
build --mode nicp LIST --out DIR: the depth frames of a TUM list (depth.txt: "time file")
tracked by NICP against the merged model of the frames before (thesis 5.1.4), or frame to
frame; writes DIR/trajectory.tum (world_T_camera, the first frame is the world, the list's
stamps) and DIR/model.ply (the merged model's points and normals, or every 10th frame's).
  --method M            nicp (default), point-to-plane or snicp (cross-product normals,
                        3 iterations at 1/4, 1/2 and full resolution)
  --snicp-scales S,S,...  snicp: the pyramid's levels, coarse to fine, as divisors of the
                        --image-scale resolution (default 4,2,1, thesis 5.3)
  --tracking T          model (default: frame to model, each frame merged; a frame that
                        fails is not) or frame (frame to frame)
  --identity-guess      start every pair from identity (default: the previous motion)
  --max-frames N        only the first N frames
  --image-scale N       every N-th pixel and row (default 1); SNICP's pyramid is built on
                        this resolution
  --iterations N        (default 10)
  --inverse-depth-weights  weigh each pair by 1 / (d_i d_j), the points' depths (Eq. 6.7)
  --flat-curvature S    sigma below which a surface is a disc (Eq. 5.2; default 0.02)
  --radius M[,M...]     the statistics radius R; frame to frame NICP refines coarse to
                        fine as `register` does (default 0.1,0.03); the model tracker fits
                        over the first, unless --model-fine-radius
  --model-fine-radius   nicp, frame to model: the last 5 iterations pair the frame's and
                        the rendered model's normals refitted over the last --radius
  --intrinsics FX,FY,CX,CY  (default 525,525,319.5,239.5)
  --json                a summary: frames, failures, frame_ms_p50/p95 (statistics of the
                        new frame + registration), registration_ms_p50, load_ms_p50
)";

namespace {

constexpr std::string_view kTool = "flat2d-map";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

struct Args {
  std::string list, out;
  NicpBuildOptions options;
  bool json = false;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&] { return maps::cli::OptionValue(kTool, argc, argv, i); };
    auto integer = [&](std::int64_t max) { return static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 1, max)); };
    if (arg == "--mode") {
      if (std::string_view(value()) != "nicp") Fail(1, "build: --mode nicp expected here");
    } else if (arg == "--out") a.out = value();
    else if (arg == "--method") {
      const std::string_view name = value();
      a.options.snicp = name == "snicp";
      const auto method = a.options.snicp ? registration::RegistrationMethod::kNicp : registration::ParseMethod(name);
      if (!method) Fail(1, "build: --method is nicp, snicp or point-to-plane");
      a.options.method = *method;
    } else if (arg == "--tracking") {
      const std::string_view tracking = value();
      if (tracking != "model" && tracking != "frame") Fail(1, "build: --tracking is model or frame");
      a.options.frame_to_model = tracking == "model";
    } else if (arg == "--identity-guess") a.options.constant_velocity = false;
    else if (arg == "--max-frames") a.options.max_frames = integer(1 << 30);
    else if (arg == "--image-scale") a.options.frames.image_scale = integer(8);
    else if (arg == "--iterations") a.options.nicp.iterations = integer(1000);
    else if (arg == "--snicp-scales") {
      a.options.snicp_options.scales = maps::cli::ParseCoarseToFine(kTool, arg, value(), 64);
    }
    else if (arg == "--inverse-depth-weights") a.options.nicp.inverse_depth_weights = true;
    else if (arg == "--model-fine-radius") a.options.model_fine_radius = true;
    else if (arg == "--flat-curvature") {
      a.options.frames.depth_statistics.flat_curvature =
          static_cast<float>(maps::cli::ParseNumberIn(kTool, arg, value(), 0.0, 1.0));
    }
    else if (arg == "--radius") {
      const std::vector<double> radii = maps::cli::ParseDecreasing(kTool, arg, value(), 1e-4, 100.0);
      a.options.frame_radii.assign(radii.begin(), radii.end());
      a.options.frames.depth_statistics.radius_m = a.options.frame_radii.front();
    }
    else if (arg == "--intrinsics") {
      const auto v = maps::cli::ParseNumberList(kTool, arg, value(), 4);
      a.options.frames.intrinsics = {640, 480, static_cast<float>(v[0]), static_cast<float>(v[1]),
                                     static_cast<float>(v[2]), static_cast<float>(v[3])};
    } else if (arg == "--json") a.json = true;
    else if (!arg.starts_with("-") && a.list.empty()) a.list = std::string(arg);
    else Fail(1, "build --mode nicp: unknown argument " + std::string(arg) + "\n" + kNicpBuildUsage);
  }
  if (a.list.empty() || a.out.empty()) Fail(1, std::string("build --mode nicp needs LIST and --out DIR\n") + kNicpBuildUsage);
  if (a.options.model_fine_radius &&
      (a.options.snicp || !a.options.frame_to_model || a.options.frame_radii.size() < 2)) {
    Fail(1, "build: --model-fine-radius refines the model tracker (--tracking model) of nicp or point-to-plane "
            "over the last of two or more --radius values");
  }
  return a;
}

}  // namespace

int NicpBuildCommand(int argc, char** argv) {
  const Args a = ParseArgs(argc, argv);
  const auto summary = BuildFromDepthList(a.list, a.options, a.out);
  if (!summary.ok()) Fail(2, summary.error().message);
  const NicpBuildSummary& s = *summary;
  const auto frame = evaluation::PercentilesOf(s.frame_ms);
  const double registration_p50 = evaluation::PercentilesOf(s.registration_ms).p50;
  const double load_p50 = evaluation::PercentilesOf(s.load_ms).p50;
  const double merge_p50 = evaluation::PercentilesOf(s.merge_ms).p50;
  if (a.json) {
    std::printf("{\"frames\": %d, \"failures\": %d, \"frame_ms_p50\": %.3f, \"frame_ms_p95\": %.3f, "
                "\"registration_ms_p50\": %.3f, \"merge_ms_p50\": %.3f, \"load_ms_p50\": %.3f, \"model_points\": %zu, "
                "\"method\": \"%s\", \"tracking\": \"%s\"}\n",
                s.frames, s.failures, frame.p50, frame.p95, registration_p50, merge_p50, load_p50, s.model_points,
                a.options.snicp ? "snicp" : std::string(registration::MethodName(a.options.method)).c_str(),
                a.options.frame_to_model ? "model" : "frame");
  } else {
    std::printf("%d frames tracked, %d failed registrations\n", s.frames, s.failures);
    std::printf("per frame: %.1f ms p50, %.1f ms p95 (statistics + registration + merging); registration %.1f ms "
                "p50; rendering and merging %.1f ms p50; reading %.1f ms p50\n",
                frame.p50, frame.p95, registration_p50, merge_p50, load_p50);
    std::printf("wrote %s/trajectory.tum and %s/model.ply (%zu points)\n", a.out.c_str(), a.out.c_str(), s.model_points);
  }
  return 0;
}

}  // namespace flat2d::localization::tools
