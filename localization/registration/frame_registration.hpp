// Registering one range frame to another (thesis 5.1): the finder chosen by the target's
// kind (projective in an organized target's own image, KD-tree otherwise), the metric by
// the method, and the time it took.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "localization/registration/nicp_options.hpp"
#include "localization/registration/registration_result.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::registration {

enum class RegistrationMethod { kNicp, kPointToPlane };

std::string_view MethodName(RegistrationMethod method);
std::optional<RegistrationMethod> ParseMethod(std::string_view name);
// The error a method minimizes: point-to-plane is NICP with Omega^n = 0.
ErrorMetric MetricOf(RegistrationMethod method);

enum class CorrespondenceMode { kAuto, kProjective, kKdTree };

// The R that NicpOptions::normal_weight is given for.
inline constexpr double kNormalWeightRadiusM = 0.1;
// options.normal_weight for normals fitted over `radius_m`: scaled by (R / 0.1 m)^2
// (nicp_options.hpp).
double NormalWeightAt(const NicpOptions& options, float radius_m);

struct FrameRegistration {
  RegistrationResult result;
  bool kdtree = false;   // which finder ran
  double seconds = 0.0;  // correspondences and optimisation, one thread (not the statistics)
};

// options.normal_weight is scaled by (target R / 0.1 m)^2 (nicp_options.hpp).
FrameRegistration RegisterFrames(const maps::range3d::RangeFrame& target, const maps::range3d::RangeFrame& source,
                                 const Eigen::Isometry3d& guess, RegistrationMethod method, NicpOptions options,
                                 CorrespondenceMode mode = CorrespondenceMode::kAuto);

// A wide first stage for guesses far from the optimum (docs/benchmarks.md, "An acquisition
// stage for far guesses"). Projective pairs assume a near guess: turned 30 deg or more, a
// pixel of an organized target sees another surface, and the gates of Eq. 5.6 and 5.8
// reject nearly every pair. This stage pairs by KD-tree on (p, alpha n) (Eq. 6.10) with
// both gates opened, at the frames' first radius, over every source point (thinned to every
// 2nd or 4th, it lost a fifth to a third of the 30 deg guesses). The thesis' stages refine
// from its estimate, or from the guess when it fails. Not in the thesis, so off unless
// asked for.
struct AcquisitionOptions {
  int iterations = 0;             // 0: no acquisition stage
  float max_distance_m = 3.0F;    // eps_d while acquiring
  float min_normal_dot = 0.5F;    // eps_n while acquiring: 60 deg
  float curvature_floor = 0.02F;  // Eq. 5.7 while acquiring: flat patches agree (nicp_options.hpp)
};

// The acquisition stage alone (its `seconds` include the KD-tree's construction).
FrameRegistration Acquire(const maps::range3d::RangeFrame& target, const maps::range3d::RangeFrame& source,
                          const Eigen::Isometry3d& guess, RegistrationMethod method, NicpOptions options,
                          const AcquisitionOptions& acquisition);

// Coarse-to-fine statistics radii (docs/benchmarks.md, "Coarse-to-fine statistics radius"):
// normals fitted over a wide R are smooth enough to pull a pair in from afar, normals over
// a small one follow the surface more closely and so land nearer the truth. The first
// radius is the one the frames were prepared with; before each later one both frames are
// refitted. options.iterations is shared out by IterationsPerRadius, so the work of the
// iterations is that of one radius. `seconds` includes the refits.
// A stage that fails ends the registration with its result. With acquisition.iterations
// > 0 the acquisition stage runs first, its iterations on top of options.iterations.
FrameRegistration RegisterFramesOverRadii(const maps::range3d::RangeFrameOptions& frames,
                                          const std::vector<float>& radii_m, maps::range3d::RangeFrame& target,
                                          maps::range3d::RangeFrame& source, const Eigen::Isometry3d& guess,
                                          RegistrationMethod method, const NicpOptions& options,
                                          CorrespondenceMode mode = CorrespondenceMode::kAuto,
                                          const AcquisitionOptions& acquisition = {});

// Iterations per radius of RegisterFramesOverRadii: the last radius refines from near the
// optimum and takes kFineRadiusIterations (half of them all when fewer than twice that);
// the earlier radii share the rest evenly, the first ones taking the remainder.
inline constexpr int kFineRadiusIterations = 5;
std::vector<int> IterationsPerRadius(int iterations, std::size_t radii);

// The radius refined to after the sensor's R (docs/benchmarks.md, "Coarse-to-fine
// statistics radius"). Depth cameras, after 0.1 m (5.1.1): over the 50 TUM fr1/rpy pairs
// 0.03 m beat 0.05 and 0.1 in accuracy, and starting at 0.1 keeps the frame skips and
// perturbations that 0.03 alone loses. LiDAR, after 0.3 m: 0.05 m brings the VLP-16
// sweeps (0.53 to 0.31 mm) and KITTI pairs (25.2 to 22.9 mm) nearer their truth and the
// HDL-32E pair's rotation nearer its references; 0.1 m is nearer on KITTI (22.3 mm) and
// keeps all of the HDL-32E 20 deg basin (0.05 m: 90 %), but leaves VLP-16 at 0.53 mm.
inline constexpr float kDepthFineRadiusM = 0.03F;
inline constexpr float kLidarFineRadiusM = 0.05F;

}  // namespace flat2d::localization::registration
