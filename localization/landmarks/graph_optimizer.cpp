#include "localization/landmarks/graph_optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/SparseCholesky>

#include "hal/common/time.hpp"
#include "localization/landmarks/landmark_factors.hpp"

namespace flat2d::localization::landmarks {

namespace {

// A gradient this small (in cost units per metre or radian) is rounding of a zero error.
constexpr double kStationaryGradient = 1e-9;

// The nodes a step moves; the factors stay where they are.
struct NodeState {
  std::vector<PoseNode> poses;
  std::vector<PlaneNode> planes;
  std::vector<LineNode> lines;
  std::vector<PointNode> points;
};

NodeState SaveNodes(const LandmarkGraph& graph) { return {graph.poses, graph.planes, graph.lines, graph.points}; }

void RestoreNodes(NodeState state, LandmarkGraph& graph) {
  graph.poses = std::move(state.poses);
  graph.planes = std::move(state.planes);
  graph.lines = std::move(state.lines);
  graph.points = std::move(state.points);
}

// x [+] dx (Eq. 3.28) node by node.
void ApplyStep(const VariableLayout& layout, const Eigen::VectorXd& dx, LandmarkGraph& graph) {
  for (int p = layout.first_free_pose; p < static_cast<int>(graph.poses.size()); ++p) {
    PoseNode& node = graph.poses[static_cast<std::size_t>(p)];
    node.world_T_vehicle = RetractPose(node.world_T_vehicle, dx.segment<6>(layout.PoseOffset(p)));
  }
  for (std::size_t l = 0; l < graph.planes.size(); ++l) {
    if (layout.plane_offset[l] >= 0) graph.planes[l].plane = Retract(graph.planes[l].plane, dx.segment<3>(layout.plane_offset[l]));
  }
  for (std::size_t l = 0; l < graph.lines.size(); ++l) {
    if (layout.line_offset[l] >= 0) graph.lines[l].line = Retract(graph.lines[l].line, dx.segment<4>(layout.line_offset[l]));
  }
  for (std::size_t l = 0; l < graph.points.size(); ++l) {
    if (layout.point_offset[l] >= 0) graph.points[l].point += dx.segment<3>(layout.point_offset[l]);  // F4's retraction
  }
}

// Marquardt's damping: each diagonal entry scaled by 1 + lambda, so metres and radians are
// damped alike. The tiny absolute term keeps a variable with no information solvable.
Eigen::SparseMatrix<double> Damped(const Eigen::SparseMatrix<double>& h, double lambda) {
  Eigen::SparseMatrix<double> damped = h;
  damped.diagonal() = h.diagonal() * (1.0 + lambda) + Eigen::VectorXd::Constant(h.rows(), 1e-12);
  return damped;
}

using Solver = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;

// One LM iteration: tries steps with growing lambda until one lowers the cost. Returns the
// new cost, or the old one when every step up to max_lambda was refused.
double TryStep(const Eigen::SparseMatrix<double>& h, const Eigen::VectorXd& b, double cost, const VariableLayout& layout,
               const OptimizerOptions& options, Solver& solver, double& lambda, LandmarkGraph& graph,
               OptimizationResult& result) {
  while (lambda <= options.max_lambda) {
    ++result.iterations;
    solver.factorize(Damped(h, lambda));
    if (solver.info() != Eigen::Success) {
      result.factorization_failed = true;
      return cost;
    }
    const Eigen::VectorXd dx = solver.solve(-b);
    NodeState before = SaveNodes(graph);
    ApplyStep(layout, dx, graph);
    const double new_cost = Cost(graph, layout, options.kernel);
    if (std::isfinite(new_cost) && new_cost < cost) {
      lambda = std::max(lambda / 10.0, 1e-9);
      return new_cost;
    }
    RestoreNodes(std::move(before), graph);
    ++result.refused_steps;
    lambda *= 10.0;
  }
  return cost;
}

}  // namespace

OptimizationResult OptimizeGraph(LandmarkGraph& graph, const OptimizerOptions& options, int max_iterations,
                                 int first_free_pose) {
  const auto start = std::chrono::steady_clock::now();
  OptimizationResult result;
  const VariableLayout layout = MakeLayout(graph, options.min_landmark_observations, first_free_pose);
  result.variables = layout.dimension;
  if (layout.dimension == 0 || max_iterations <= 0) return result;
  NormalEquations eq = Linearize(graph, layout, options.kernel);
  result.initial_cost = result.final_cost = eq.cost;
  // Already at a stationary point (e.g. odometry alone, which every factor agrees with).
  if (eq.b.lpNorm<Eigen::Infinity>() <= kStationaryGradient) {
    result.converged = true;
    result.downweighted_factors = eq.downweighted;
    result.milliseconds = MillisecondsSince(start);
    return result;
  }
  Solver solver;
  bool analyzed = false;
  double lambda = options.initial_lambda;
  while (result.iterations < max_iterations) {
    const Eigen::SparseMatrix<double> h = Assemble(eq, layout, graph);
    if (!analyzed) solver.analyzePattern(h);  // the pattern is the layout's: once per call
    analyzed = true;
    const double cost = TryStep(h, eq.b, eq.cost, layout, options, solver, lambda, graph, result);
    if (result.factorization_failed || !(cost < eq.cost)) {
      result.converged = !result.factorization_failed;  // no step lowers the cost
      break;
    }
    const bool small = eq.cost - cost <= options.min_relative_decrease * eq.cost;
    eq = Linearize(graph, layout, options.kernel);
    if (small) {
      result.converged = true;
      break;
    }
  }
  result.final_cost = eq.cost;
  result.downweighted_factors = eq.downweighted;
  result.milliseconds = MillisecondsSince(start);
  return result;
}

}  // namespace flat2d::localization::landmarks
