#include "localization/registration/nicp.hpp"

#include "localization/registration/linear_system.hpp"

namespace flat2d::localization::registration {

const char* FailureName(RegistrationFailure failure) {
  switch (failure) {
    case RegistrationFailure::kNone: return "none";
    case RegistrationFailure::kTooFewCorrespondences: return "too_few_correspondences";
    case RegistrationFailure::kDegenerate: return "degenerate";
  }
  return "unknown";
}

RegistrationResult Nicp::Register(const maps::range3d::SurfelCloud& target, CorrespondenceFinder& finder,
                                  const maps::range3d::SurfelCloud& source, const Eigen::Isometry3d& guess) {
  RegistrationResult result;
  result.target_T_source = guess;
  for (int iteration = 0; iteration < options_.iterations; ++iteration) {
    const Eigen::Isometry3f transform = result.target_T_source.cast<float>();
    finder.Find(source, transform, options_, pairs_);
    const LinearSystem system = BuildLinearSystem(target, source, pairs_, transform, options_);
    result.iterations = iteration + 1;
    result.correspondences = static_cast<int>(pairs_.size());
    result.inliers = system.inliers;
    result.chi2 = system.chi2;
    result.information = system.H;
    if (system.inliers < options_.min_inliers) {
      result.failure = RegistrationFailure::kTooFewCorrespondences;
      return result;
    }
    const double lambda = options_.damping * system.H.diagonal().mean();
    const Matrix6d damped = system.H + lambda * Matrix6d::Identity();
    const Eigen::LDLT<Matrix6d> solver(damped);
    const Vector6d increment = solver.solve(-system.b);
    if (solver.info() != Eigen::Success || !increment.allFinite()) {
      result.failure = RegistrationFailure::kDegenerate;
      return result;
    }
    result.target_T_source = ApplyIncrement(increment, result.target_T_source);
    if (increment.lpNorm<Eigen::Infinity>() < options_.convergence_step) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace flat2d::localization::registration
