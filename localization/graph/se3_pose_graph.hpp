// An SE(3) pose graph, the 3D counterpart of pose_graph.hpp (thesis 3.4.2, "local maps" of
// 6.3.3): nodes with world_T_node estimates and the between factors that tie them, as read
// from g2o's VERTEX_SE3:QUAT / EDGE_SE3:QUAT records (g2o_se3_io.hpp). Plain data:
// se3_graph_optimizer.hpp moves the estimates, se3_costs.hpp scores them. Factors refer to
// nodes by their index in `nodes`; `Se3Node::id` keeps the file's vertex id.
//
// Tangent vectors (increments, the rows and columns of information matrices) are ordered
// translation first, rotation second, as g2o's EDGE_SE3:QUAT information is.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace flat2d::localization::graph {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Se3Node {
  int id = 0;                                              // the file's vertex id
  Eigen::Isometry3d estimate = Eigen::Isometry3d::Identity();  // world_T_node
  bool fixed = false;         // held constant by the optimizer (g2o FIX)
  bool has_estimate = false;  // false when the file had no vertex line for it
};

// Measurement z = from_T_to with its information (inverse covariance) over the error of
// se3_factors.hpp (G2), rows and columns (translation, quaternion vector part).
struct Se3BetweenFactor {
  std::size_t from = 0;
  std::size_t to = 0;
  Eigen::Isometry3d measurement = Eigen::Isometry3d::Identity();
  Matrix6d information = Matrix6d::Identity();
};

struct Se3PoseGraph {
  std::vector<Se3Node> nodes;
  std::vector<Se3BetweenFactor> betweens;

  std::size_t AddNode(const Eigen::Isometry3d& estimate, bool fixed = false) {
    nodes.push_back({static_cast<int>(nodes.size()), estimate, fixed, true});
    return nodes.size() - 1;
  }
};

}  // namespace flat2d::localization::graph
