// Loop closures in the SE(3) graph of local maps behind a robust kernel (thesis 6.3.3: a
// wrong closure must not bend the map): dynamic covariance scaling (Agarwal et al., ICRA
// 2013), the closed form of switchable constraints (Suenderhauf and Protzel, IROS 2012).
// Closure k's information is scaled by s_k^2 with
//
//     s_k = min(1, 2 Phi / (Phi + chi2_k)),
//
// chi2_k its term at the current solution under its own information. The graph is solved,
// the scales re-evaluated, and again (iteratively reweighted least squares) until no scale
// moves by more than a tolerance. The first solve takes every closure at full weight, so
// a few wrong closures among consistent ones are the terms left straining, and fall.
// A closure ending below min_kept_scale is reported as dropped: it pulls with less than a
// quarter of its information.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "localization/graph/graph_optimizer.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::loops {

struct RobustClosureOptions {
  double phi = 10.0;  // chi2 (6 degrees of freedom) up to which a closure keeps its whole weight
  int max_rounds = 10;
  double scale_tolerance = 1e-3;
  double min_kept_scale = 0.5;
  graph::OptimizerOptions optimizer;
};

struct RobustClosureResult {
  std::vector<double> scales;  // per closure, in the order given
  std::vector<bool> kept;      // scale >= min_kept_scale
  int rounds = 0;
  int iterations = 0;          // the optimizer's, over all rounds
  double seconds = 0.0;
  bool converged = false;      // the last solve converged
};

// `closures`: indices into graph.betweens of the loop closures; the other factors keep
// their information. Leaves the closures' information scaled by s_k^2.
RobustClosureResult OptimizeWithRobustClosures(graph::Se3PoseGraph& graph, std::span<const std::size_t> closures,
                                               const RobustClosureOptions& options);

// After OptimizeWithRobustClosures: the chain's weak ties (the odometry's guesses across
// failed registrations, thesis Fig. 6.7) behind the same kernel against the kept closures,
// so that consistent closures can overrule a wrong guess. `closures` and `closure_kept` as
// OptimizeWithRobustClosures had and gave them; the dropped ones are left out of this solve
// (their information is restored after it). Judged in the same solve as the closures, a
// false closure could tear the chain open at a weak tie instead of being dropped. Without a
// tie or a kept closure nothing is solved (each tie's scale 1). Adds its rounds, iterations
// and time to `totals`; returns the ties' scales.
std::vector<double> JudgeWeakTies(graph::Se3PoseGraph& graph, std::span<const std::size_t> ties,
                                  std::span<const std::size_t> closures, const std::vector<bool>& closure_kept,
                                  const RobustClosureOptions& options, RobustClosureResult& totals);

}  // namespace flat2d::localization::loops
