#include "localization/loops/trajectory_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "hal/trajectory/pose_interpolation.hpp"
#include "localization/graph/se3_factors.hpp"

namespace flat2d::localization::loops {

namespace {

using graph::Matrix6d;
using graph::Vector6d;

struct Pair {
  Eigen::Isometry3d reference;  // map_T_pose of the reference, interpolated
  int current = 0;              // index into the current path
};

// Eq. 6.13's term: toVector(T_m^r^-1 T T_n^c), the G2 error of a pose T T_n^c measured as T_m^r.
Vector6d ShapeError(const Eigen::Isometry3d& reference_T_current, const Eigen::Isometry3d& reference_pose,
                    const Eigen::Isometry3d& current_pose) {
  return graph::Se3BetweenError(Eigen::Isometry3d::Identity(), reference_T_current * current_pose, reference_pose);
}

}  // namespace

ShapeLinearization LinearizeShapeError(const Eigen::Isometry3d& reference_T_current, const Eigen::Isometry3d& reference_pose,
                                       const Eigen::Isometry3d& current_pose) {
  // With X = T B and T [+] d = (R_T Exp(w), t_T + dt) (G1): X's rotation becomes
  // R_X Exp(R_B^T w) and its position t_X + dt - R_T [t_B]x w, so the G3 Jacobian with
  // respect to X, times that map, is the one with respect to T.
  const auto between = graph::LinearizeSe3Between(Eigen::Isometry3d::Identity(), reference_T_current * current_pose, reference_pose);
  Matrix6d chain = Matrix6d::Zero();
  chain.topLeftCorner<3, 3>().setIdentity();
  chain.topRightCorner<3, 3>() = -reference_T_current.linear() * graph::Hat(current_pose.translation());
  chain.bottomRightCorner<3, 3>() = current_pose.linear().transpose();
  return {between.error, between.jacobian_j * chain};
}

namespace {

// Gauss-Newton on the pairs, each weighted by a Huber kernel on its error's norm.
Eigen::Isometry3d SolveEq613(Eigen::Isometry3d transform, const std::vector<Pair>& pairs,
                             std::span<const Eigen::Isometry3d> current, const ShapeAlignmentOptions& options) {
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    Matrix6d hessian = Matrix6d::Zero();
    Vector6d gradient = Vector6d::Zero();
    for (const Pair& pair : pairs) {
      const ShapeLinearization term =
          LinearizeShapeError(transform, pair.reference, current[static_cast<std::size_t>(pair.current)]);
      const double norm = term.error.norm();
      const double weight = norm > options.huber_m ? options.huber_m / norm : 1.0;
      hessian += weight * term.jacobian.transpose() * term.jacobian;
      gradient += weight * term.jacobian.transpose() * term.error;
    }
    const Vector6d step = hessian.ldlt().solve(-gradient);
    if (!step.allFinite()) break;
    transform = graph::Retract(transform, step);
    if (step.norm() < 1e-7) break;
  }
  return transform;
}

// Steps 2 and 4: current pose n with the reference pose `offset_m` further along the
// reference's path than n is along the current's, from the seed outward in both
// directions; within span_m of the seed, and, when `gate` is given, only while the pair's
// position error under `transform` stays within it.
std::vector<Pair> PairsAtOffset(std::span<const Eigen::Isometry3d> reference, std::span<const double> reference_arcs,
                                std::span<const Eigen::Isometry3d> current, std::span<const double> current_arcs,
                                int current_seed, double offset_m, double span_m, const Eigen::Isometry3d& transform,
                                std::optional<double> gate_m) {
  const double seed_arc = current_arcs[static_cast<std::size_t>(current_seed)];
  const auto partner = [&](int n) -> std::optional<Pair> {
    const double arc = current_arcs[static_cast<std::size_t>(n)];
    const double reference_arc = arc + offset_m;
    if (std::abs(arc - seed_arc) > span_m || reference_arc < 0.0 || reference_arc > reference_arcs.back()) return std::nullopt;
    Pair pair{PoseAlongPath(reference, reference_arcs, reference_arc), n};
    if (gate_m && ShapeError(transform, pair.reference, current[static_cast<std::size_t>(n)]).head<3>().norm() > *gate_m) {
      return std::nullopt;
    }
    return pair;
  };
  std::vector<Pair> before, after;
  for (int n = current_seed - 1; n >= 0; --n) {
    auto pair = partner(n);
    if (!pair) break;
    before.push_back(*pair);
  }
  for (int n = current_seed; n < static_cast<int>(current.size()); ++n) {
    auto pair = partner(n);
    if (!pair) break;
    after.push_back(*pair);
  }
  std::vector<Pair> pairs(before.rbegin(), before.rend());
  pairs.insert(pairs.end(), after.begin(), after.end());
  return pairs;
}

struct Fit {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  std::vector<Pair> pairs;
  double mean_squared_error = std::numeric_limits<double>::infinity();
};

// Steps 2-4 for one path offset between the passes.
Fit FitAtOffset(std::span<const Eigen::Isometry3d> reference, std::span<const double> reference_arcs,
                std::span<const Eigen::Isometry3d> current, std::span<const double> current_arcs, int current_seed,
                double offset_m, const Eigen::Isometry3d& initial, const ShapeAlignmentOptions& options) {
  Fit fit;
  fit.pairs = PairsAtOffset(reference, reference_arcs, current, current_arcs, current_seed, offset_m, options.initial_span_m,
                            initial, std::nullopt);
  if (fit.pairs.size() < 3) return fit;  // fewer than three poses cannot hold a 3D transform
  fit.transform = SolveEq613(initial, fit.pairs, current, options);
  for (int round = 0; round < options.max_reassociations; ++round) {
    std::vector<Pair> grown = PairsAtOffset(reference, reference_arcs, current, current_arcs, current_seed, offset_m,
                                            std::numeric_limits<double>::infinity(), fit.transform,
                                            options.max_pair_distance_m);
    if (grown.size() < 3 || grown.size() == fit.pairs.size()) break;
    fit.pairs = std::move(grown);
    fit.transform = SolveEq613(fit.transform, fit.pairs, current, options);
  }
  double sum = 0.0;
  for (const Pair& pair : fit.pairs) {
    sum += ShapeError(fit.transform, pair.reference, current[static_cast<std::size_t>(pair.current)]).squaredNorm();
  }
  fit.mean_squared_error = sum / static_cast<double>(fit.pairs.size());
  return fit;
}

ShapeAlignment Summarize(const Eigen::Isometry3d& transform, const std::vector<Pair>& pairs,
                         std::span<const Eigen::Isometry3d> current, std::span<const double> current_arcs) {
  ShapeAlignment result;
  result.reference_T_current = transform;
  result.pairs = static_cast<int>(pairs.size());
  if (pairs.empty()) return result;
  double translation = 0.0;
  double rotation = 0.0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const Vector6d error = ShapeError(transform, pairs[k].reference, current[static_cast<std::size_t>(pairs[k].current)]);
    translation += error.head<3>().squaredNorm();
    rotation += std::pow(2.0 * std::asin(std::min(1.0, error.tail<3>().norm())), 2);
    if (k > 0 && pairs[k].current == pairs[k - 1].current + 1) {
      result.matched_length_m += current_arcs[static_cast<std::size_t>(pairs[k].current)] -
                                 current_arcs[static_cast<std::size_t>(pairs[k - 1].current)];
    }
  }
  result.rms_translation_m = std::sqrt(translation / static_cast<double>(pairs.size()));
  result.rms_rotation_rad = std::sqrt(rotation / static_cast<double>(pairs.size()));
  return result;
}

}  // namespace

std::vector<double> ArcLengths(std::span<const Eigen::Isometry3d> path) {
  std::vector<double> arcs(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i) {
    arcs[i] = arcs[i - 1] + (path[i].translation() - path[i - 1].translation()).norm();
  }
  return arcs;
}

Eigen::Isometry3d PoseAlongPath(std::span<const Eigen::Isometry3d> path, std::span<const double> arc_lengths,
                                double arc_m) {
  if (arc_m <= arc_lengths.front()) return path.front();
  if (arc_m >= arc_lengths.back()) return path.back();
  const auto upper = std::upper_bound(arc_lengths.begin(), arc_lengths.end(), arc_m);
  const std::size_t i = static_cast<std::size_t>(upper - arc_lengths.begin()) - 1;
  const double span = arc_lengths[i + 1] - arc_lengths[i];
  return hal::trajectory::InterpolatePose(path[i], path[i + 1], span > 0.0 ? (arc_m - arc_lengths[i]) / span : 0.0);
}

ShapeAlignment AlignTrajectories(std::span<const Eigen::Isometry3d> reference, std::span<const Eigen::Isometry3d> current,
                                 int reference_seed, int current_seed, const ShapeAlignmentOptions& options) {
  const auto in_range = [](int index, std::size_t size) { return index >= 0 && static_cast<std::size_t>(index) < size; };
  if (!in_range(reference_seed, reference.size()) || !in_range(current_seed, current.size())) return {};
  const std::vector<double> reference_arcs = ArcLengths(reference);
  const std::vector<double> current_arcs = ArcLengths(current);

  const Eigen::Isometry3d initial = reference[static_cast<std::size_t>(reference_seed)] *
                                    current[static_cast<std::size_t>(current_seed)].inverse();  // step 1
  // Step 5: the offset between the passes' path lengths, on a coarse then a fine grid
  // around the association's; not when the association's own fit is hopeless.
  const double seed_offset = reference_arcs[static_cast<std::size_t>(reference_seed)] -
                             current_arcs[static_cast<std::size_t>(current_seed)];
  Fit best = FitAtOffset(reference, reference_arcs, current, current_arcs, current_seed, seed_offset, initial, options);
  if (!(best.mean_squared_error <= options.search_limit_m * options.search_limit_m)) {
    return Summarize(best.transform, best.pairs, current, current_arcs);
  }
  double best_offset = seed_offset;
  for (const double step : {options.offset_search_m / 4.0, options.offset_search_m / 16.0}) {
    const double centre = best_offset;
    for (int k = -4; k <= 4; ++k) {
      if (k == 0 || (step < options.offset_search_m / 4.0 && std::abs(k) > 2)) continue;
      const double offset = centre + k * step;
      Fit fit = FitAtOffset(reference, reference_arcs, current, current_arcs, current_seed, offset, initial, options);
      if (fit.mean_squared_error < best.mean_squared_error) {
        best = std::move(fit);
        best_offset = offset;
      }
    }
  }
  return Summarize(best.transform, best.pairs, current, current_arcs);
}

}  // namespace flat2d::localization::loops
