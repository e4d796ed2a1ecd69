#include "localization/loops/closure_validation.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include <Eigen/Eigenvalues>

#include "localization/registration/correspondence_finder.hpp"
#include "localization/registration/nicp.hpp"

namespace flat2d::localization::loops {
namespace {

// How far off its plane a flat pair pulls in full under the shipped K (nicp_options.hpp).
constexpr double kWinsorizedReachM = 0.1;

std::size_t PointsWithNormals(const maps::range3d::SurfelCloud& cloud) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) n += cloud.has_normal(i) ? 1 : 0;
  return n;
}

std::string Format(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

// The rounds of step 1: NICP from the guess with eps_d shrinking.
registration::RegistrationResult RegisterInRounds(const maps::range3d::SurfelCloud& reference,
                                                  const maps::range3d::SurfelCloud& current, const Eigen::Isometry3d& guess,
                                                  const ClosureValidationOptions& options) {
  registration::KdTreeCorrespondenceFinder finder(reference, options.nicp.kdtree_alpha);
  registration::RegistrationResult result;
  result.target_T_source = guess;
  for (const float distance : options.round_distances_m) {
    registration::NicpOptions round = options.nicp;
    round.max_distance_m = distance;
    // K of Eq. 4.11 grown with the round's reach: under the shipped K a flat pair stops
    // pulling 10 cm off its plane, and pairs a lane apart would barely move the map.
    const double reach = std::max(1.0, static_cast<double>(distance) / kWinsorizedReachM);
    round.chi2_bound = options.nicp.chi2_bound * reach * reach;
    registration::Nicp nicp(round);
    result = nicp.Register(reference, finder, current, result.target_T_source);
    if (!result.ok()) break;
  }
  return result;
}

// Step 3: another fit as good as `fit`, found from it moved along its weakest direction.
std::string Ambiguity(const maps::range3d::SurfelCloud& reference, const maps::range3d::SurfelCloud& current,
                      const registration::RegistrationResult& fit, const ClosureValidationOptions& options) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(fit.information.topLeftCorner<3, 3>());
  const Eigen::Vector3d weakest = eigen.eigenvectors().col(0);  // ascending eigenvalues
  for (const double sign : {1.0, -1.0}) {
    const Eigen::Isometry3d start = Eigen::Translation3d(sign * options.ambiguity_shift_m * weakest) * fit.target_T_source;
    const registration::RegistrationResult other = RegisterInRounds(reference, current, start, options);
    if (!other.ok() || !other.target_T_source.matrix().allFinite()) continue;
    const double apart = (other.target_T_source.translation() - fit.target_T_source.translation()).norm();
    const double ratio = static_cast<double>(other.inliers) / std::max(fit.inliers, 1);
    if (apart > options.ambiguity_separation_m && ratio >= options.ambiguity_inlier_ratio) {
      return Format("ambiguous: another fit %.2f m away with %.2f of the inliers", apart, ratio);
    }
  }
  return {};
}

double InlierShare(const maps::range3d::SurfelCloud& a, const maps::range3d::SurfelCloud& b, int inliers) {
  const std::size_t smaller = std::min(PointsWithNormals(a), PointsWithNormals(b));
  return smaller > 0 ? static_cast<double>(inliers) / static_cast<double>(smaller) : 0.0;
}

}  // namespace

std::string FindAlias(const maps::range3d::SurfelCloud& current, const ClosureValidation& fit,
                      const AliasNeighbour& neighbour, const ClosureValidationOptions& options) {
  const Eigen::Isometry3d& reference_T_current = fit.result.target_T_source;
  const registration::RegistrationResult other = RegisterInRounds(*neighbour.map, current, reference_T_current, options);
  if (!other.ok() || !other.target_T_source.matrix().allFinite() || other.inliers <= 0) return {};
  const Eigen::Isometry3d elsewhere = neighbour.reference_T_neighbour * other.target_T_source;
  const double apart = (elsewhere.translation() - reference_T_current.translation()).norm();
  const double ratio = InlierShare(*neighbour.map, current, other.inliers) / std::max(fit.inlier_share, 1e-12);
  const double chi2 = other.chi2 / other.inliers;
  if (apart <= options.ambiguity_separation_m || ratio < options.ambiguity_inlier_ratio ||
      chi2 > options.max_chi2_per_inlier) {
    return {};
  }
  return "aliased: map " + std::to_string(neighbour.index) +
         Format(" fits as well, %.2f m away (%.2f of the inliers)", apart, ratio);
}

ClosureValidation ValidateClosure(const maps::range3d::SurfelCloud& reference, const maps::range3d::SurfelCloud& current,
                                  const Eigen::Isometry3d& guess, const ClosureValidationOptions& options) {
  ClosureValidation v;
  v.result = RegisterInRounds(reference, current, guess, options);
  if (!v.result.ok()) {
    v.reason = std::string("registration failed: ") + registration::FailureName(v.result.failure);
    return v;
  }
  v.inlier_share = InlierShare(reference, current, v.result.inliers);
  v.chi2_per_inlier = v.result.inliers > 0 ? v.result.chi2 / v.result.inliers : 0.0;
  const Eigen::Isometry3d correction = guess.inverse() * v.result.target_T_source;
  const double correction_m = correction.translation().norm();
  const double correction_rad = Eigen::AngleAxisd(correction.rotation()).angle();
  if (!v.result.target_T_source.matrix().allFinite()) {
    v.reason = "registration diverged";
  } else if (v.inlier_share < options.min_inlier_share) {
    v.reason = Format("inliers %.3f of the smaller map, below %.3f", v.inlier_share, options.min_inlier_share);
  } else if (v.chi2_per_inlier > options.max_chi2_per_inlier) {
    v.reason = Format("chi2 per inlier %.3f above %.3f", v.chi2_per_inlier, options.max_chi2_per_inlier);
  } else if (correction_m > options.max_correction_m || correction_rad > options.max_correction_rad) {
    v.reason = Format("moved %.2f m / %.3f rad from the guess", correction_m, correction_rad);
  } else if (options.ambiguity_shift_m > 0.0) {
    v.reason = Ambiguity(reference, current, v.result, options);
    v.accepted = v.reason.empty();
  } else {
    v.accepted = true;
  }
  return v;
}

}  // namespace flat2d::localization::loops
