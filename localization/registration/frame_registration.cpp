#include "localization/registration/frame_registration.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>

#include "localization/registration/correspondence_finder.hpp"
#include "localization/registration/nicp.hpp"

namespace flat2d::localization::registration {

namespace {

struct MethodEntry {
  RegistrationMethod method;
  std::string_view name;
};
constexpr std::array<MethodEntry, 2> kMethods{{{RegistrationMethod::kNicp, "nicp"},
                                               {RegistrationMethod::kPointToPlane, "point-to-plane"}}};

}  // namespace

std::string_view MethodName(RegistrationMethod method) {
  for (const MethodEntry& entry : kMethods) {
    if (entry.method == method) return entry.name;
  }
  return "unknown";
}

std::optional<RegistrationMethod> ParseMethod(std::string_view name) {
  for (const MethodEntry& entry : kMethods) {
    if (entry.name == name) return entry.method;
  }
  return std::nullopt;
}

ErrorMetric MetricOf(RegistrationMethod method) {
  return method == RegistrationMethod::kPointToPlane ? ErrorMetric::kPointToPlane : ErrorMetric::kNicp;
}

double NormalWeightAt(const NicpOptions& options, float radius_m) {
  const double ratio = static_cast<double>(radius_m) / kNormalWeightRadiusM;
  return options.normal_weight * ratio * ratio;
}

FrameRegistration RegisterFrames(const maps::range3d::RangeFrame& target, const maps::range3d::RangeFrame& source,
                                 const Eigen::Isometry3d& guess, RegistrationMethod method, NicpOptions options,
                                 CorrespondenceMode mode) {
  options.metric = MetricOf(method);
  options.normal_weight = NormalWeightAt(options, target.statistics_radius_m);
  const auto start = std::chrono::steady_clock::now();
  FrameRegistration registration;
  registration.kdtree = mode == CorrespondenceMode::kKdTree || (mode == CorrespondenceMode::kAuto && !target.organized());
  std::unique_ptr<CorrespondenceFinder> finder;
  if (registration.kdtree) {
    finder = std::make_unique<KdTreeCorrespondenceFinder>(target.cloud, options.kdtree_alpha);
  } else {
    finder = std::make_unique<ProjectiveCorrespondenceFinder>(target.cloud, target.projection, &target.image);
  }
  registration.result = Nicp(options).Register(target.cloud, *finder, source.cloud, guess);
  registration.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return registration;
}

FrameRegistration Acquire(const maps::range3d::RangeFrame& target, const maps::range3d::RangeFrame& source,
                          const Eigen::Isometry3d& guess, RegistrationMethod method, NicpOptions options,
                          const AcquisitionOptions& acquisition) {
  options.iterations = acquisition.iterations;
  options.max_distance_m = acquisition.max_distance_m;
  options.min_normal_dot = acquisition.min_normal_dot;
  options.curvature_floor = acquisition.curvature_floor;
  return RegisterFrames(target, source, guess, method, options, CorrespondenceMode::kKdTree);
}

std::vector<int> IterationsPerRadius(int iterations, std::size_t radii) {
  std::vector<int> counts(std::max<std::size_t>(radii, 1), 0);
  if (counts.size() == 1) {
    counts[0] = iterations;
    return counts;
  }
  counts.back() = std::min(kFineRadiusIterations, iterations / 2);
  const int coarse = iterations - counts.back();
  const auto stages = static_cast<int>(counts.size()) - 1;
  for (int stage = 0; stage < stages; ++stage) {
    counts[static_cast<std::size_t>(stage)] = coarse / stages + (stage < coarse % stages ? 1 : 0);
  }
  return counts;
}

FrameRegistration RegisterFramesOverRadii(const maps::range3d::RangeFrameOptions& frames,
                                          const std::vector<float>& radii_m, maps::range3d::RangeFrame& target,
                                          maps::range3d::RangeFrame& source, const Eigen::Isometry3d& guess,
                                          RegistrationMethod method, const NicpOptions& options,
                                          CorrespondenceMode mode, const AcquisitionOptions& acquisition) {
  const std::vector<int> counts = IterationsPerRadius(options.iterations, radii_m.size());
  FrameRegistration total;
  total.result.target_T_source = guess;
  if (acquisition.iterations > 0) {
    const FrameRegistration acquired = Acquire(target, source, guess, method, options, acquisition);
    if (acquired.result.ok()) total.result.target_T_source = acquired.result.target_T_source;
    total.result.iterations = acquired.result.iterations;
    total.seconds = acquired.seconds;
  }
  double refit_seconds = 0.0;
  for (std::size_t stage = 0; stage < counts.size(); ++stage) {
    if (counts[stage] == 0) continue;
    if (stage > 0) {
      const auto start = std::chrono::steady_clock::now();
      maps::range3d::RefitStatistics(frames, radii_m[stage], target);
      maps::range3d::RefitStatistics(frames, radii_m[stage], source);
      refit_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    NicpOptions stage_options = options;
    stage_options.iterations = counts[stage];
    const FrameRegistration step =
        RegisterFrames(target, source, total.result.target_T_source, method, stage_options, mode);
    const int iterations = total.result.iterations + step.result.iterations;
    const double seconds = total.seconds + step.seconds;
    total = step;
    total.result.iterations = iterations;
    total.seconds = seconds;
    if (!step.result.ok()) break;
  }
  total.seconds += refit_seconds;
  return total;
}

}  // namespace flat2d::localization::registration
