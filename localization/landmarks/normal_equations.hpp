// The normal equations of the landmark graph (thesis 3.4.2, Eq. 3.72-3.73): H dx = -b with
// H = sum J^T W Omega J and b = sum J^T W Omega e over every factor, W the robust kernel's
// IRLS weight (robust_kernel.hpp), built block by block and assembled into the sparse lower
// triangle that Eigen's SimplicialLDLT reads.
//
// Steps: VariableLayout numbers the variables (the free pose nodes, 6 entries each; pose 0 is
// the gauge and always fixed; then the planes, 3 each, the lines, 4 each, and the points, 3
// each, that have enough observations) and gives every (pose, landmark) pair its off-diagonal block once per
// structure; Linearize fills the blocks at the current estimate; Assemble writes them as a
// sparse matrix whose pattern depends only on the layout, so one symbolic analysis serves
// every iteration of a solve; Cost evaluates the robust cost alone, for the step test.
#pragma once

#include <vector>

#include <Eigen/Sparse>

#include "localization/landmarks/landmark_graph.hpp"
#include "localization/landmarks/robust_kernel.hpp"

namespace flat2d::localization::landmarks {

struct KernelChoice {
  RobustKernel kernel = RobustKernel::kCauchy;
  double width_sigmas = 3.0;
};

struct VariableLayout {
  int first_free_pose = 1;         // poses before it are held fixed (pose 0 always: the gauge)
  int free_poses = 0;
  std::vector<int> plane_offset;  // into dx, or -1 for a plane left out of the solve
  std::vector<int> line_offset;
  std::vector<int> point_offset;
  int dimension = 0;
  // The observations that touch a free landmark, and per such observation its (pose,
  // landmark) block, or -1 when the pose is fixed.
  std::vector<int> plane_factors;
  std::vector<int> line_factors;
  std::vector<int> point_factors;
  std::vector<int> plane_pair;  // parallel to plane_factors
  std::vector<int> line_pair;   // parallel to line_factors
  std::vector<int> point_pair;  // parallel to point_factors
  int plane_pairs = 0;
  int line_pairs = 0;
  int point_pairs = 0;

  bool IsFree(int pose) const { return pose >= first_free_pose; }
  int PoseOffset(int pose) const { return 6 * (pose - first_free_pose); }  // free poses only
};

// Landmarks with fewer than `min_observations` factors are left out: one sighting says
// nothing about the trajectory, and leaving them out keeps clutter out of the solve. With
// first_free_pose > 1 the solve is a window: the poses from first_free_pose on, the
// landmarks they observed, and every factor on those (fixed poses then only hold the
// landmarks where older observations put them). Building it scans every observation once.
VariableLayout MakeLayout(const LandmarkGraph& graph, int min_observations, int first_free_pose);

struct NormalEquations {
  std::vector<Eigen::Matrix<double, 6, 6>> pose_diagonal;  // per pose node (0 unused)
  std::vector<Eigen::Matrix<double, 6, 6>> odometry_block;  // d(to) x d(from), per factor
  std::vector<Eigen::Matrix3d> plane_diagonal;             // per plane
  std::vector<Eigen::Matrix4d> line_diagonal;
  std::vector<Eigen::Matrix3d> point_diagonal;
  std::vector<Eigen::Matrix<double, 3, 6>> plane_pair_block;  // d(plane) x d(pose)
  std::vector<Eigen::Matrix<double, 4, 6>> line_pair_block;
  std::vector<Eigen::Matrix<double, 3, 6>> point_pair_block;
  Eigen::VectorXd b;
  double cost = 0.0;         // sum of rho(e^T Omega e): odometry unweighted, landmarks robust
  int downweighted = 0;      // landmark factors with weight below 1/2: likely wrong associations
};

NormalEquations Linearize(const LandmarkGraph& graph, const VariableLayout& layout, const KernelChoice& kernel);

// The lower triangle of H (Eq. 3.72).
Eigen::SparseMatrix<double> Assemble(const NormalEquations& equations, const VariableLayout& layout,
                                     const LandmarkGraph& graph);

// The cost of Linearize without the Jacobians.
double Cost(const LandmarkGraph& graph, const VariableLayout& layout, const KernelChoice& kernel);

}  // namespace flat2d::localization::landmarks
