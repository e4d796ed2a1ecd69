#include "localization/registration/snicp.hpp"

#include <algorithm>
#include <chrono>

#include "localization/registration/correspondence_finder.hpp"
#include "localization/registration/nicp.hpp"

namespace flat2d::localization::registration {

SnicpFrame MakeSnicpFrame(const hal::cloud::DepthImage& depth, const maps::range3d::RangeFrameOptions& frames,
                          const SnicpOptions& options) {
  SnicpFrame frame;
  maps::range3d::CrossProductNormals normals(options.normals);
  const int working_scale = std::max(frames.image_scale, 1);  // the pyramid's "full" level
  for (const int scale : options.scales) {
    maps::range3d::RangeFrame level = maps::range3d::UnprojectDepth(depth, frames, scale * working_scale);
    normals.Compute(level.image, level.cloud);
    level.statistics_radius_m = static_cast<float>(kNormalWeightRadiusM);  // the thesis' weight, unscaled
    frame.levels.push_back(std::move(level));
  }
  return frame;
}

bool PassOverSparseLevel(bool finest, const Eigen::Isometry3d& level_guess, RegistrationResult& result) {
  if (finest || result.failure != RegistrationFailure::kTooFewCorrespondences) return false;
  result.target_T_source = level_guess;
  return true;
}

FrameRegistration RegisterSnicp(const SnicpFrame& target, const SnicpFrame& source, const Eigen::Isometry3d& guess,
                                NicpOptions nicp, const SnicpOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  nicp.iterations = options.iterations_per_level;
  FrameRegistration registration;
  registration.result.target_T_source = guess;
  int iterations = 0;
  const std::size_t levels = std::min(target.levels.size(), source.levels.size());
  for (std::size_t level = 0; level < levels; ++level) {
    const maps::range3d::RangeFrame& t = target.levels[level];
    ProjectiveCorrespondenceFinder finder(t.cloud, t.projection, &t.image);
    const Eigen::Isometry3d level_guess = registration.result.target_T_source;
    registration.result = Nicp(nicp).Register(t.cloud, finder, source.levels[level].cloud, level_guess);
    iterations += registration.result.iterations;
    if (PassOverSparseLevel(level + 1 == levels, level_guess, registration.result)) continue;
    if (!registration.result.ok()) break;
  }
  registration.result.iterations = iterations;
  registration.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return registration;
}

}  // namespace flat2d::localization::registration
