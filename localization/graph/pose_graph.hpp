// An SE(2) pose graph: nodes with pose estimates and the factors that tie them (between,
// prior, max-mixture; the math is in se2_factors.hpp). It is plain data: files are read into
// it (g2o_io.hpp, toro_io.hpp), graph_optimizer.hpp moves the estimates, graph_costs.hpp
// scores them. Factors refer to nodes by their index in `nodes`; `PoseNode::id` keeps the
// file's vertex id so a graph writes back with the ids it was read with.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "localization/graph/se2_factors.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::graph {

struct PoseNode {
  int id = 0;                   // the file's vertex id
  Se2 estimate;                 // world_T_node
  bool fixed = false;           // held constant by the optimizer (g2o FIX)
  bool has_estimate = false;    // false when the file had no vertex line for it
};

// Measurement z = from_T_to with information (inverse covariance) over F2's error.
struct BetweenFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Se2 measurement;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  AngleResidual angle = AngleResidual::kWrapped;
};

// The node's pose against a fixed world pose (F4).
struct PriorFactor {
  std::size_t node = 0;
  Se2 measurement;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

// A between factor whose Gaussian is a max-mixture (F5), e.g. a loop closure that may be
// wrong: the mixture's components all use the between error F2 (wrapped angle).
struct MaxMixtureBetweenFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Se2 measurement;
  MaxMixture mixture;
};

// A prior whose Gaussian is a max-mixture (F4, F5), e.g. a global match that may be wrong.
struct MaxMixturePriorFactor {
  std::size_t node = 0;
  Se2 measurement;
  MaxMixture mixture;
};

struct PoseGraph {
  std::vector<PoseNode> nodes;
  std::vector<BetweenFactor> betweens;
  std::vector<PriorFactor> priors;
  std::vector<MaxMixtureBetweenFactor> mixture_betweens;
  std::vector<MaxMixturePriorFactor> mixture_priors;

  std::size_t AddNode(const Se2& estimate, bool fixed = false) {
    nodes.push_back({static_cast<int>(nodes.size()), estimate, fixed, true});
    return nodes.size() - 1;
  }
  std::size_t FactorCount() const {
    return betweens.size() + priors.size() + mixture_betweens.size() + mixture_priors.size();
  }
};

}  // namespace flat2d::localization::graph
