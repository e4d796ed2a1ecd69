#include "localization/loops/robust_closures.hpp"

#include <algorithm>
#include <cmath>

#include "localization/graph/se3_costs.hpp"
#include "localization/graph/se3_graph_optimizer.hpp"

namespace flat2d::localization::loops {
namespace {

double DcsScale(double chi2, double phi) { return std::min(1.0, 2.0 * phi / (phi + chi2)); }

}  // namespace

RobustClosureResult OptimizeWithRobustClosures(graph::Se3PoseGraph& graph, std::span<const std::size_t> closures,
                                               const RobustClosureOptions& options) {
  RobustClosureResult result;
  std::vector<graph::Matrix6d> information;
  for (const std::size_t k : closures) information.push_back(graph.betweens[k].information);
  result.scales.assign(closures.size(), 1.0);
  for (result.rounds = 1; result.rounds <= options.max_rounds; ++result.rounds) {
    for (std::size_t c = 0; c < closures.size(); ++c) {
      graph.betweens[closures[c]].information = result.scales[c] * result.scales[c] * information[c];
    }
    const graph::OptimizationResult solved = graph::Optimize(graph, options.optimizer);
    result.iterations += solved.iterations;
    result.seconds += solved.seconds;
    result.converged = solved.converged();
    double largest_change = 0.0;
    for (std::size_t c = 0; c < closures.size(); ++c) {
      graph::Se3BetweenFactor unscaled = graph.betweens[closures[c]];
      unscaled.information = information[c];
      const double chi2 = graph::BetweenCost(unscaled, graph.nodes[unscaled.from].estimate, graph.nodes[unscaled.to].estimate);
      const double scale = DcsScale(chi2, options.phi);
      largest_change = std::max(largest_change, std::abs(scale - result.scales[c]));
      result.scales[c] = scale;
    }
    if (largest_change < options.scale_tolerance) break;
  }
  result.rounds = std::min(result.rounds, options.max_rounds);
  for (const double s : result.scales) result.kept.push_back(s >= options.min_kept_scale);
  return result;
}

std::vector<double> JudgeWeakTies(graph::Se3PoseGraph& graph, std::span<const std::size_t> ties,
                                  std::span<const std::size_t> closures, const std::vector<bool>& closure_kept,
                                  const RobustClosureOptions& options, RobustClosureResult& totals) {
  if (ties.empty()) return {};
  if (std::find(closure_kept.begin(), closure_kept.end(), true) == closure_kept.end()) {
    return std::vector<double>(ties.size(), 1.0);
  }
  std::vector<std::pair<std::size_t, graph::Matrix6d>> dropped;
  for (std::size_t c = 0; c < closures.size(); ++c) {
    if (closure_kept[c]) continue;
    graph::Matrix6d& information = graph.betweens[closures[c]].information;
    dropped.emplace_back(closures[c], information);
    information.setZero();
  }
  const RobustClosureResult judged = OptimizeWithRobustClosures(graph, ties, options);
  for (const auto& [factor, information] : dropped) graph.betweens[factor].information = information;
  totals.rounds += judged.rounds;
  totals.iterations += judged.iterations;
  totals.seconds += judged.seconds;
  return judged.scales;
}

}  // namespace flat2d::localization::loops
