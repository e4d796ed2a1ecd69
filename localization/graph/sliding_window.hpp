// The daemon's L2G pose graph over a bounded window (thesis 7.2.1, DESIGN.md "L2G factor
// graph"): nodes are vehicle poses global_T_vehicle at match times, linked by odometry
// between factors; scan matches are unary max-mixture factors (the match Gaussian against
// a broad null hypothesis, Olson & Agarwal 2012) so a wrong match cannot drag the pose;
// GNSS fixes or an initial pose are unary Gaussian priors.
//
// Steps:
//  1. AddNode appends a node; when the window already holds `capacity` nodes, the oldest is
//     first marginalized into a Gaussian prior on the nodes it was connected to
//     (marginal_prior.hpp, M1) instead of being thrown away: fixed memory, no lost
//     information (up to the frozen linearization of the past).
//  2. AddOdometry / AddMatch / AddPrior attach factors. Between factors may span at most
//     `max_between_span` nodes (B), so the Gauss-Newton matrix is block-banded.
//  3. Solve runs Gauss-Newton on the component retraction (se2_factors.hpp F1, thesis
//     Alg. 6), re-selecting every max-mixture component at each linearization, with
//     Levenberg-Marquardt damping when a step raises the cost; each linear system is
//     solved by block-banded Cholesky in O(N B^2) (banded_solver.hpp). It returns the
//     newest pose and its marginal covariance (banded_solver.hpp B3).
// Costs are chi-squares: sum e^T Omega e (g2o's convention) plus F5's mixture offsets plus
// the marginal prior's M2 term (the marginalized factors' remaining chi-square).
//
// Memory: nodes live in a ring of `capacity` slots; each slot has room for
// `max_between_per_node` between factors (stored on their older node, so removing the
// oldest node removes exactly its slot) and `max_unary_per_node` unary factors. Everything
// is allocated in Create; Add*, Solve and marginalization never touch the heap (errors on
// bad input build a message, which does).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "localization/graph/banded_solver.hpp"
#include "localization/graph/marginal_prior.hpp"
#include "localization/graph/se2_factors.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::graph {

// Nodes are numbered 0, 1, 2, ... in the order they were added, for the graph's lifetime.
using NodeId = std::int64_t;

struct SlidingWindowOptions {
  // N, nodes kept. Memory and solve time grow linearly; 500 nodes at 10 Hz hold 50 s.
  int capacity = 500;
  // B, the largest id distance of a between factor (1 = consecutive nodes only), at most
  // kMaxBetweenSpan. It is the bandwidth of the solver and the size of the marginal prior.
  int max_between_span = 1;
  // Between factors whose older node is a given node (odometry, odometry from a second
  // source, ...); bounds the factor storage at capacity x this.
  int max_between_per_node = 2;
  // Unary factors (matches, GNSS, initial pose) on one node; storage capacity x this.
  int max_unary_per_node = 2;
  // Marginalize the oldest node into the prior (M1) when the window is full; false drops it
  // with its factors (what a fixed-lag smoother without marginalization does; for ablation).
  bool marginalize = true;
  // Damp a step that raises the cost (Levenberg-Marquardt); false: plain Gauss-Newton.
  bool levenberg_marquardt = true;
  // Converged when no increment component exceeds this (m or rad).
  double step_tolerance = 1e-7;
};

Status ValidateOptions(const SlidingWindowOptions& options);

// The broad Gaussian that explains a wrong match (F5, MakeNullHypothesisMixture).
struct NullHypothesis {
  double weight = 0.0;             // prior probability that a match is wrong, in (0, 1)
  double information_scale = 0.0;  // null information / match information, in (0, 1)
};

struct WindowSolution {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;       // linear solves, including rejected Levenberg-Marquardt steps
  bool converged = false;   // the last step was below step_tolerance
  int null_matches = 0;     // matches on their null hypothesis at the solution
  NodeId newest = 0;
  Se2 newest_global_T_vehicle;
  // Marginal covariance of the newest pose's components (x, y, theta), as Se2's convention.
  Eigen::Matrix3d newest_covariance = Eigen::Matrix3d::Zero();
};

class SlidingWindowGraph {
 public:
  static Result<SlidingWindowGraph> Create(const SlidingWindowOptions& options);

  // Appends a node at `time` (strictly after the newest) with an initial estimate,
  // marginalizing the oldest node first when the window is full.
  Result<NodeId> AddNode(TimeNs time, const Se2& global_T_vehicle);
  // A between factor: `from_T_to` measured with `information`, 0 < to - from <= B.
  Status AddOdometry(NodeId from, NodeId to, const Se2& from_T_to,
                     const Eigen::Matrix3d& information);
  // A scan match: the node's global pose measured with `information`, a max-mixture
  // against `null_hypothesis`.
  Status AddMatch(NodeId node, const Se2& global_T_vehicle, const Eigen::Matrix3d& information,
                  const NullHypothesis& null_hypothesis);
  // A Gaussian on the node's global pose (GNSS, an initial or operator-set pose).
  Status AddPrior(NodeId node, const Se2& global_T_vehicle, const Eigen::Matrix3d& information);

  // Up to max_iterations Gauss-Newton / Levenberg-Marquardt steps from the current
  // estimates; 0 only evaluates the cost and the covariance at the current estimates. Fails when the window is empty or not anchored (no prior or match reaches
  // the newest node, so its covariance is unbounded); the estimates are then unchanged.
  Result<WindowSolution> Solve(int max_iterations);
  // Drops every node, factor and the marginal prior (a relocalized vehicle starts afresh);
  // ids go on from where they were.
  void Clear();

  int size() const { return size_; }
  bool Contains(NodeId id) const { return size_ > 0 && id >= oldest_ && id < oldest_ + size_; }
  NodeId oldest_id() const { return oldest_; }
  NodeId newest_id() const { return oldest_ + size_ - 1; }
  std::int64_t marginalized_count() const { return oldest_; }
  std::optional<Se2> Estimate(NodeId id) const;
  std::optional<TimeNs> Time(NodeId id) const;
  // Matches of the node on their null component at the last linearization.
  std::optional<int> NullMatches(NodeId id) const;
  const MarginalPrior& marginal_prior() const { return prior_; }

 private:
  struct BetweenFactor {
    int span = 0;  // to - from
    Se2 measurement;
    Eigen::Matrix3d information;
  };
  struct UnaryFactor {
    Se2 measurement;
    MaxMixture mixture;
    bool is_match = false;
    std::size_t component = 0;  // chosen at the last linearization
  };
  struct Node {
    TimeNs time = 0;
    int between_count = 0;
    int unary_count = 0;
  };

  explicit SlidingWindowGraph(const SlidingWindowOptions& options);

  std::size_t Slot(int position) const;
  int Position(NodeId id) const { return static_cast<int>(id - oldest_); }
  BetweenFactor& Between(int position, int k);
  UnaryFactor& Unary(int position, int k);
  Status AddUnary(NodeId node, const Se2& measurement, const MaxMixture& mixture, bool is_match);

  // sliding_window_solve.cpp
  double Assemble();  // linearizes all factors at estimates_, fills system_, returns cost
  void MarginalizeOldest();
  void DropOldest();

  SlidingWindowOptions options_;
  std::vector<Node> nodes_;                // capacity, a ring starting at head_
  std::vector<BetweenFactor> between_;     // capacity x max_between_per_node
  std::vector<UnaryFactor> unary_;         // capacity x max_unary_per_node
  std::vector<Se2> estimates_;             // capacity, window order (oldest first)
  std::vector<Se2> backup_;                // capacity, estimates before a step
  BlockBandedSystem system_;
  MarginalPrior prior_;
  std::size_t head_ = 0;  // slot of the oldest node
  int size_ = 0;
  NodeId oldest_ = 0;
};

}  // namespace flat2d::localization::graph
