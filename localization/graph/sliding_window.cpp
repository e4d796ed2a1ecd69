#include "localization/graph/sliding_window.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <string>

namespace flat2d::localization::graph {
namespace {

// Information matrices must be symmetric to this relative tolerance.
constexpr double kSymmetryTolerance = 1e-9;

bool IsFinite(const Se2& pose) {
  return std::isfinite(pose.x()) && std::isfinite(pose.y()) && std::isfinite(pose.theta());
}

Status CheckInformation(const Eigen::Matrix3d& information) {
  if (!information.allFinite()) return MakeError("information matrix is not finite");
  const double scale = information.cwiseAbs().maxCoeff();
  if ((information - information.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * scale) {
    return MakeError("information matrix is not symmetric");
  }
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return MakeError("information matrix is not positive definite");
  return Status::Ok();
}

}  // namespace

Status ValidateOptions(const SlidingWindowOptions& options) {
  if (options.max_between_span < 1 || options.max_between_span > kMaxBetweenSpan) {
    return MakeError("max_between_span must be in [1, " + std::to_string(kMaxBetweenSpan) + "]");
  }
  if (options.capacity <= options.max_between_span) {
    return MakeError("capacity must exceed max_between_span");
  }
  if (options.max_between_per_node < 1 || options.max_unary_per_node < 1) {
    return MakeError("max_between_per_node and max_unary_per_node must be >= 1");
  }
  if (!(options.step_tolerance > 0.0)) return MakeError("step_tolerance must be positive");
  return Status::Ok();
}

Result<SlidingWindowGraph> SlidingWindowGraph::Create(const SlidingWindowOptions& options) {
  if (Status status = ValidateOptions(options); !status.ok()) return status.error();
  return SlidingWindowGraph(options);
}

SlidingWindowGraph::SlidingWindowGraph(const SlidingWindowOptions& options)
    : options_(options),
      nodes_(static_cast<std::size_t>(options.capacity)),
      between_(static_cast<std::size_t>(options.capacity * options.max_between_per_node)),
      unary_(static_cast<std::size_t>(options.capacity * options.max_unary_per_node)),
      estimates_(static_cast<std::size_t>(options.capacity)),
      backup_(static_cast<std::size_t>(options.capacity)),
      system_(options.capacity, options.max_between_span) {}

std::size_t SlidingWindowGraph::Slot(int position) const {
  return (head_ + static_cast<std::size_t>(position)) % nodes_.size();
}

SlidingWindowGraph::BetweenFactor& SlidingWindowGraph::Between(int position, int k) {
  return between_[Slot(position) * static_cast<std::size_t>(options_.max_between_per_node) +
                  static_cast<std::size_t>(k)];
}

SlidingWindowGraph::UnaryFactor& SlidingWindowGraph::Unary(int position, int k) {
  return unary_[Slot(position) * static_cast<std::size_t>(options_.max_unary_per_node) +
                static_cast<std::size_t>(k)];
}

void SlidingWindowGraph::Clear() {
  oldest_ += size_;
  size_ = 0;
  head_ = 0;
  prior_ = MarginalPrior{};
}

Result<NodeId> SlidingWindowGraph::AddNode(TimeNs time, const Se2& global_T_vehicle) {
  if (!IsFinite(global_T_vehicle)) return MakeError("node estimate is not finite");
  if (size_ > 0 && time <= nodes_[Slot(size_ - 1)].time) {
    return MakeError("node time must be after the newest node's");
  }
  if (size_ == options_.capacity) {
    if (options_.marginalize) {
      MarginalizeOldest();
    } else {
      DropOldest();
    }
  }
  nodes_[Slot(size_)] = Node{.time = time, .between_count = 0, .unary_count = 0};
  estimates_[static_cast<std::size_t>(size_)] = global_T_vehicle;
  ++size_;
  return newest_id();
}

Status SlidingWindowGraph::AddOdometry(NodeId from, NodeId to, const Se2& from_T_to,
                                       const Eigen::Matrix3d& information) {
  if (!Contains(from) || !Contains(to)) return MakeError("odometry node is not in the window");
  if (to <= from || to - from > options_.max_between_span) {
    return MakeError("odometry must go forward by 1 to max_between_span nodes");
  }
  if (!IsFinite(from_T_to)) return MakeError("odometry measurement is not finite");
  if (Status status = CheckInformation(information); !status.ok()) return status;
  Node& node = nodes_[Slot(Position(from))];
  if (node.between_count == options_.max_between_per_node) {
    return MakeError("node already has max_between_per_node between factors");
  }
  Between(Position(from), node.between_count++) =
      BetweenFactor{.span = static_cast<int>(to - from), .measurement = from_T_to,
                    .information = information};
  return Status::Ok();
}

Status SlidingWindowGraph::AddMatch(NodeId node, const Se2& global_T_vehicle,
                                    const Eigen::Matrix3d& information,
                                    const NullHypothesis& null_hypothesis) {
  if (!(null_hypothesis.weight > 0.0 && null_hypothesis.weight < 1.0) ||
      !(null_hypothesis.information_scale > 0.0 && null_hypothesis.information_scale < 1.0)) {
    return MakeError("null hypothesis weight and information scale must be in (0, 1)");
  }
  if (Status status = CheckInformation(information); !status.ok()) return status;
  return AddUnary(node, global_T_vehicle,
                  MakeNullHypothesisMixture(information, null_hypothesis.weight,
                                            null_hypothesis.information_scale),
                  /*is_match=*/true);
}

Status SlidingWindowGraph::AddPrior(NodeId node, const Se2& global_T_vehicle,
                                    const Eigen::Matrix3d& information) {
  if (Status status = CheckInformation(information); !status.ok()) return status;
  MaxMixture single;
  single.components[0] = {1.0, information};
  single.size = 1;
  return AddUnary(node, global_T_vehicle, single, /*is_match=*/false);
}

Status SlidingWindowGraph::AddUnary(NodeId node, const Se2& measurement,
                                    const MaxMixture& mixture, bool is_match) {
  if (!Contains(node)) return MakeError("unary factor node is not in the window");
  if (!IsFinite(measurement)) return MakeError("unary measurement is not finite");
  Node& slot = nodes_[Slot(Position(node))];
  if (slot.unary_count == options_.max_unary_per_node) {
    return MakeError("node already has max_unary_per_node unary factors");
  }
  Unary(Position(node), slot.unary_count++) = UnaryFactor{
      .measurement = measurement, .mixture = mixture, .is_match = is_match, .component = 0};
  return Status::Ok();
}

std::optional<Se2> SlidingWindowGraph::Estimate(NodeId id) const {
  if (!Contains(id)) return std::nullopt;
  return estimates_[static_cast<std::size_t>(Position(id))];
}

std::optional<TimeNs> SlidingWindowGraph::Time(NodeId id) const {
  if (!Contains(id)) return std::nullopt;
  return nodes_[Slot(Position(id))].time;
}

std::optional<int> SlidingWindowGraph::NullMatches(NodeId id) const {
  if (!Contains(id)) return std::nullopt;
  const int position = Position(id);
  const std::size_t first = Slot(position) * static_cast<std::size_t>(options_.max_unary_per_node);
  int count = 0;
  for (int k = 0; k < nodes_[Slot(position)].unary_count; ++k) {
    const UnaryFactor& factor = unary_[first + static_cast<std::size_t>(k)];
    if (factor.is_match && factor.component != 0) ++count;
  }
  return count;
}

}  // namespace flat2d::localization::graph
