// Registering one range frame to another (thesis 5.1): the finder chosen by the target's
// kind (projective in an organized target's own image, KD-tree otherwise), the metric by
// the method, and the time it took.
#pragma once

#include <optional>
#include <string_view>

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

struct FrameRegistration {
  RegistrationResult result;
  bool kdtree = false;   // which finder ran
  double seconds = 0.0;  // correspondences and optimisation, one thread (not the statistics)
};

// options.normal_weight is scaled by (target R / 0.1 m)^2 (nicp_options.hpp).
FrameRegistration RegisterFrames(const maps::range3d::RangeFrame& target, const maps::range3d::RangeFrame& source,
                                 const Eigen::Isometry3d& guess, RegistrationMethod method, NicpOptions options,
                                 CorrespondenceMode mode = CorrespondenceMode::kAuto);

}  // namespace flat2d::localization::registration
