#include "localization/landmarks/normal_equations.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "localization/landmarks/graph_factors.hpp"
#include "localization/landmarks/point_factor.hpp"

namespace flat2d::localization::landmarks {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// The observations on free landmarks, and one block per distinct (free pose, landmark)
// pair: a pose that saw a wall in four revolutions adds four factors into one block.
template <typename Observation>
void ActiveFactors(const std::vector<Observation>& observations, const std::vector<int>& landmark_offset,
                   int first_free_pose, std::vector<int>* factors, std::vector<int>* pairs, int* pair_count) {
  std::unordered_map<std::uint64_t, int> slots;
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const Observation& o = observations[i];
    if (landmark_offset[static_cast<std::size_t>(o.landmark)] < 0) continue;
    factors->push_back(static_cast<int>(i));
    if (o.pose < first_free_pose) {
      pairs->push_back(-1);
      continue;
    }
    const std::uint64_t key = (static_cast<std::uint64_t>(o.pose) << 32) | static_cast<std::uint32_t>(o.landmark);
    pairs->push_back(slots.emplace(key, static_cast<int>(slots.size())).first->second);
  }
  *pair_count = static_cast<int>(slots.size());
}

// Offsets from `next` on for the landmarks with enough observations, one of them by a free pose.
template <typename Node, typename Observation>
std::vector<int> LandmarkOffsets(const std::vector<Node>& nodes, const std::vector<Observation>& observations,
                                 int min_observations, int first_free_pose, int size, int* next) {
  std::vector<char> seen_by_free(nodes.size(), 0);
  for (const Observation& o : observations) {
    if (o.pose >= first_free_pose) seen_by_free[static_cast<std::size_t>(o.landmark)] = 1;
  }
  std::vector<int> offset(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].observations < min_observations || !seen_by_free[i]) continue;
    offset[i] = *next;
    *next += size;
  }
  return offset;
}

ObservationGeometry GeometryOf(const LandmarkGraph& graph, const Matrix6d& sensor_of_vehicle, int pose,
                               const Eigen::Isometry3d& world_T_anchor) {
  return ObservationGeometry{graph.poses[static_cast<std::size_t>(pose)].world_T_vehicle, graph.vehicle_T_sensor,
                             world_T_anchor, sensor_of_vehicle};
}

// Adds a dense block at (row, col) of the lower triangle; on the diagonal only its lower part.
template <typename Block>
void AddBlock(const Block& block, int row, int col, bool diagonal, Triplets* triplets) {
  for (int c = 0; c < block.cols(); ++c) {
    for (int r = diagonal ? c : 0; r < block.rows(); ++r) triplets->emplace_back(row + r, col + c, block(r, c));
  }
}

// Each (pose, landmark) block once, at the first active observation that names it.
template <typename Block, typename Observation>
void AddPairBlocks(const std::vector<Block>& blocks, const std::vector<int>& factors, const std::vector<int>& pair,
                   const std::vector<Observation>& observations, const std::vector<int>& landmark_offset,
                   const VariableLayout& layout, Triplets* triplets) {
  std::vector<char> written(blocks.size(), 0);
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const int slot = pair[k];
    if (slot < 0 || written[static_cast<std::size_t>(slot)]) continue;
    written[static_cast<std::size_t>(slot)] = 1;
    const Observation& o = observations[static_cast<std::size_t>(factors[k])];
    AddBlock(blocks[static_cast<std::size_t>(slot)], landmark_offset[static_cast<std::size_t>(o.landmark)],
             layout.PoseOffset(o.pose), false, triplets);
  }
}

// The landmark diagonals of the solved landmarks.
template <typename Block>
void AddLandmarkDiagonals(const std::vector<Block>& diagonal, const std::vector<int>& offset, Triplets* triplets) {
  for (std::size_t l = 0; l < diagonal.size(); ++l) {
    if (offset[l] >= 0) AddBlock(diagonal[l], offset[l], offset[l], true, triplets);
  }
}

// The J^T W Omega J and J^T W Omega e of one landmark factor into the equations.
template <int D>
void Accumulate(const Eigen::Matrix<double, D, 1>& error, const Eigen::Matrix<double, D, 6>& j_pose,
                const Eigen::Matrix<double, D, D>& j_landmark, const Eigen::Matrix<double, D, D>& information,
                int pose, int landmark_offset, const VariableLayout& layout, Eigen::Matrix<double, D, D>* landmark_diagonal,
                Eigen::Matrix<double, D, 6>* pair_block, const KernelChoice& kernel, NormalEquations* equations) {
  const KernelValue k = ApplyKernel(kernel.kernel, kernel.width_sigmas, error.dot(information * error));
  equations->cost += k.cost;
  if (k.weight < 0.5) ++equations->downweighted;
  const Eigen::Matrix<double, D, D> weighted = k.weight * information;
  const Eigen::Matrix<double, D, D> lt_w = j_landmark.transpose() * weighted;
  *landmark_diagonal += lt_w * j_landmark;
  equations->b.template segment<D>(landmark_offset) += lt_w * error;
  if (!layout.IsFree(pose)) return;
  const Eigen::Matrix<double, 6, D> pt_w = j_pose.transpose() * weighted;
  equations->pose_diagonal[static_cast<std::size_t>(pose)] += pt_w * j_pose;
  *pair_block += lt_w * j_pose;
  equations->b.template segment<6>(layout.PoseOffset(pose)) += pt_w * error;
}

void LinearizeOdometryFactors(const LandmarkGraph& graph, const VariableLayout& layout, NormalEquations* equations) {
  // The factors into free poses: those with `from` + 1 >= first_free_pose.
  for (std::size_t f = static_cast<std::size_t>(layout.first_free_pose - 1); f < graph.odometry.size(); ++f) {
    const OdometryFactor& factor = graph.odometry[f];
    const auto from = static_cast<std::size_t>(factor.from);
    const OdometryLinearization lin =
        LinearizeOdometry(graph.poses[from].world_T_vehicle, graph.poses[from + 1].world_T_vehicle, factor.from_T_to);
    const Vector6d omega_e = factor.information * lin.error;
    equations->cost += lin.error.dot(omega_e);
    const Matrix6d jt_to = lin.jacobian_to.transpose() * factor.information;
    equations->pose_diagonal[from + 1] += jt_to * lin.jacobian_to;
    equations->b.segment<6>(layout.PoseOffset(factor.from + 1)) += lin.jacobian_to.transpose() * omega_e;
    if (!layout.IsFree(factor.from)) continue;
    equations->pose_diagonal[from] += lin.jacobian_from.transpose() * factor.information * lin.jacobian_from;
    equations->odometry_block[f] = jt_to * lin.jacobian_from;
    equations->b.segment<6>(layout.PoseOffset(factor.from)) += lin.jacobian_from.transpose() * omega_e;
  }
}

}  // namespace

VariableLayout MakeLayout(const LandmarkGraph& graph, int min_observations, int first_free_pose) {
  VariableLayout layout;
  layout.first_free_pose = std::max(first_free_pose, 1);
  layout.free_poses = std::max(static_cast<int>(graph.poses.size()) - layout.first_free_pose, 0);
  int next = 6 * layout.free_poses;
  layout.plane_offset =
      LandmarkOffsets(graph.planes, graph.plane_observations, min_observations, layout.first_free_pose, 3, &next);
  layout.line_offset =
      LandmarkOffsets(graph.lines, graph.line_observations, min_observations, layout.first_free_pose, 4, &next);
  layout.point_offset =
      LandmarkOffsets(graph.points, graph.point_observations, min_observations, layout.first_free_pose, 3, &next);
  layout.dimension = next;
  ActiveFactors(graph.plane_observations, layout.plane_offset, layout.first_free_pose, &layout.plane_factors,
                &layout.plane_pair, &layout.plane_pairs);
  ActiveFactors(graph.line_observations, layout.line_offset, layout.first_free_pose, &layout.line_factors,
                &layout.line_pair, &layout.line_pairs);
  ActiveFactors(graph.point_observations, layout.point_offset, layout.first_free_pose, &layout.point_factors,
                &layout.point_pair, &layout.point_pairs);
  return layout;
}

NormalEquations Linearize(const LandmarkGraph& graph, const VariableLayout& layout, const KernelChoice& kernel) {
  NormalEquations eq;
  eq.pose_diagonal.assign(graph.poses.size(), Matrix6d::Zero());
  eq.odometry_block.assign(graph.odometry.size(), Matrix6d::Zero());
  eq.plane_diagonal.assign(graph.planes.size(), Eigen::Matrix3d::Zero());
  eq.line_diagonal.assign(graph.lines.size(), Eigen::Matrix4d::Zero());
  eq.point_diagonal.assign(graph.points.size(), Eigen::Matrix3d::Zero());
  eq.plane_pair_block.assign(static_cast<std::size_t>(layout.plane_pairs), Eigen::Matrix<double, 3, 6>::Zero());
  eq.line_pair_block.assign(static_cast<std::size_t>(layout.line_pairs), Eigen::Matrix<double, 4, 6>::Zero());
  eq.point_pair_block.assign(static_cast<std::size_t>(layout.point_pairs), Eigen::Matrix<double, 3, 6>::Zero());
  eq.b = Eigen::VectorXd::Zero(layout.dimension);
  LinearizeOdometryFactors(graph, layout, &eq);
  const Matrix6d a = SensorPerturbationOfVehicle(graph.vehicle_T_sensor);
  Eigen::Matrix<double, 3, 6> unused_pair3;  // a fixed pose's block (planes, points): written, never read
  Eigen::Matrix<double, 4, 6> unused_line_pair;
  for (std::size_t k = 0; k < layout.plane_factors.size(); ++k) {
    const PlaneObservation& o = graph.plane_observations[static_cast<std::size_t>(layout.plane_factors[k])];
    const auto l = static_cast<std::size_t>(o.landmark);
    const PlaneNode& node = graph.planes[l];
    const PlaneFactorLinearization lin =
        LinearizePlaneObservation(GeometryOf(graph, a, o.pose, node.world_T_anchor), node.plane, o.measured);
    const int slot = layout.plane_pair[k];
    Accumulate<3>(lin.error, lin.jacobian_pose, lin.jacobian_plane, o.information, o.pose, layout.plane_offset[l], layout,
                  &eq.plane_diagonal[l], slot < 0 ? &unused_pair3 : &eq.plane_pair_block[static_cast<std::size_t>(slot)],
                  kernel, &eq);
  }
  for (std::size_t k = 0; k < layout.line_factors.size(); ++k) {
    const LineObservation& o = graph.line_observations[static_cast<std::size_t>(layout.line_factors[k])];
    const auto l = static_cast<std::size_t>(o.landmark);
    const LineNode& node = graph.lines[l];
    const std::optional<LineFactorLinearization> lin =
        LinearizeLineObservation(GeometryOf(graph, a, o.pose, node.world_T_anchor), node.line, o.measured);
    if (!lin) continue;  // a landmark pushed to infinity contributes nothing until it returns
    const int slot = layout.line_pair[k];
    Accumulate<4>(lin->error, lin->jacobian_pose, lin->jacobian_line, o.information, o.pose, layout.line_offset[l], layout,
                  &eq.line_diagonal[l], slot < 0 ? &unused_line_pair : &eq.line_pair_block[static_cast<std::size_t>(slot)],
                  kernel, &eq);
  }
  for (std::size_t k = 0; k < layout.point_factors.size(); ++k) {
    const PointObservation& o = graph.point_observations[static_cast<std::size_t>(layout.point_factors[k])];
    const auto l = static_cast<std::size_t>(o.landmark);
    const PointNode& node = graph.points[l];
    const PointFactorLinearization lin =
        LinearizePointObservation(GeometryOf(graph, a, o.pose, node.world_T_anchor), node.point, o.measured);
    const int slot = layout.point_pair[k];
    Accumulate<3>(lin.error, lin.jacobian_pose, lin.jacobian_point, o.information, o.pose, layout.point_offset[l], layout,
                  &eq.point_diagonal[l], slot < 0 ? &unused_pair3 : &eq.point_pair_block[static_cast<std::size_t>(slot)],
                  kernel, &eq);
  }
  return eq;
}

Eigen::SparseMatrix<double> Assemble(const NormalEquations& eq, const VariableLayout& layout,
                                     const LandmarkGraph& graph) {
  Triplets triplets;
  // Bound: 21 per pose diagonal, 36 per odometry block, 6 or 10 per landmark diagonal,
  // 18 or 24 per pair block.
  triplets.reserve(static_cast<std::size_t>(57 * layout.free_poses + 10 * static_cast<int>(graph.lines.size()) +
                                            6 * static_cast<int>(graph.planes.size() + graph.points.size()) +
                                            18 * (layout.plane_pairs + layout.point_pairs) + 24 * layout.line_pairs));
  for (int p = layout.first_free_pose; p < static_cast<int>(graph.poses.size()); ++p) {
    AddBlock(eq.pose_diagonal[static_cast<std::size_t>(p)], layout.PoseOffset(p), layout.PoseOffset(p), true, &triplets);
  }
  for (std::size_t f = static_cast<std::size_t>(layout.first_free_pose); f < graph.odometry.size(); ++f) {
    const int from = graph.odometry[f].from;  // free, as is from + 1
    AddBlock(eq.odometry_block[f], layout.PoseOffset(from + 1), layout.PoseOffset(from), false, &triplets);
  }
  AddLandmarkDiagonals(eq.plane_diagonal, layout.plane_offset, &triplets);
  AddLandmarkDiagonals(eq.line_diagonal, layout.line_offset, &triplets);
  AddLandmarkDiagonals(eq.point_diagonal, layout.point_offset, &triplets);
  AddPairBlocks(eq.plane_pair_block, layout.plane_factors, layout.plane_pair, graph.plane_observations, layout.plane_offset,
                layout, &triplets);
  AddPairBlocks(eq.line_pair_block, layout.line_factors, layout.line_pair, graph.line_observations, layout.line_offset,
                layout, &triplets);
  AddPairBlocks(eq.point_pair_block, layout.point_factors, layout.point_pair, graph.point_observations, layout.point_offset,
                layout, &triplets);
  Eigen::SparseMatrix<double> h(layout.dimension, layout.dimension);
  h.setFromTriplets(triplets.begin(), triplets.end());
  return h;
}

double Cost(const LandmarkGraph& graph, const VariableLayout& layout, const KernelChoice& kernel) {
  double cost = 0.0;
  for (std::size_t f = static_cast<std::size_t>(layout.first_free_pose - 1); f < graph.odometry.size(); ++f) {
    const OdometryFactor& factor = graph.odometry[f];
    const auto from = static_cast<std::size_t>(factor.from);
    const Vector6d e = OdometryError(graph.poses[from].world_T_vehicle, graph.poses[from + 1].world_T_vehicle, factor.from_T_to);
    cost += e.dot(factor.information * e);
  }
  for (const int i : layout.plane_factors) {
    const PlaneObservation& o = graph.plane_observations[static_cast<std::size_t>(i)];
    const PlaneNode& node = graph.planes[static_cast<std::size_t>(o.landmark)];
    const Eigen::Isometry3d anchor_T_sensor = GeometryOf(graph, Matrix6d::Identity(), o.pose, node.world_T_anchor).AnchorTSensor();
    const Eigen::Vector3d e = PlaneError(anchor_T_sensor, node.plane, o.measured);
    cost += ApplyKernel(kernel.kernel, kernel.width_sigmas, e.dot(o.information * e)).cost;
  }
  for (const int i : layout.line_factors) {
    const LineObservation& o = graph.line_observations[static_cast<std::size_t>(i)];
    const LineNode& node = graph.lines[static_cast<std::size_t>(o.landmark)];
    const Eigen::Isometry3d anchor_T_sensor = GeometryOf(graph, Matrix6d::Identity(), o.pose, node.world_T_anchor).AnchorTSensor();
    const std::optional<Eigen::Vector4d> e = LineError(anchor_T_sensor, node.line, o.measured);
    if (e) cost += ApplyKernel(kernel.kernel, kernel.width_sigmas, e->dot(o.information * *e)).cost;
  }
  for (const int i : layout.point_factors) {
    const PointObservation& o = graph.point_observations[static_cast<std::size_t>(i)];
    const PointNode& node = graph.points[static_cast<std::size_t>(o.landmark)];
    const Eigen::Isometry3d anchor_T_sensor = GeometryOf(graph, Matrix6d::Identity(), o.pose, node.world_T_anchor).AnchorTSensor();
    const Eigen::Vector3d e = PointError(anchor_T_sensor, node.point, o.measured);
    cost += ApplyKernel(kernel.kernel, kernel.width_sigmas, e.dot(o.information * e)).cost;
  }
  return cost;
}

}  // namespace flat2d::localization::landmarks
