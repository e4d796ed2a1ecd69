#include "localization/tools/catacomb_build.hpp"

#include <chrono>
#include <map>
#include <random>
#include <utility>

#include "localization/loops/trajectory_shape.hpp"
#include "localization/tools/grid_run.hpp"

namespace flat2d::localization::tools {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The information of an isotropic sigma over the between error (t, q_xyz): q_xyz is about
// half the rotation vector, so its sigma is half the angle's.
graph::Matrix6d InformationOf(const FactorSigma& sigma) {
  graph::Matrix6d information = graph::Matrix6d::Zero();
  const double half_angle = 0.5 * sigma.rotation_rad;
  information.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / (sigma.translation_m * sigma.translation_m));
  information.bottomRightCorner<3, 3>().diagonal().setConstant(1.0 / (half_angle * half_angle));
  return information;
}

// A local map as the tracker closed it (step 1).
struct TrackedMap {
  Eigen::Isometry3d world_T_map;
  int first_revolution = 0;
  int last_revolution = 0;
  bool ends_in_failure = false;
};

// Local maps read back for validation: the newest map's, and the last few past ones.
class MapCache {
 public:
  explicit MapCache(const loops::LocalMapStore& store) : store_(store) {}

  Result<const maps::range3d::SurfelCloud*> Get(int index) {
    if (auto found = maps_.find(index); found != maps_.end()) return &found->second;
    auto read = store_.ReadPoints(index);
    if (!read.ok()) return read.error();
    if (maps_.size() >= kCapacity) maps_.erase(maps_.begin());  // the oldest index: revisits move forward
    return &maps_.emplace(index, std::move(*read)).first->second;
  }

 private:
  static constexpr std::size_t kCapacity = 16;
  const loops::LocalMapStore& store_;
  std::map<int, maps::range3d::SurfelCloud> maps_;
};

class CatacombBuilder {
 public:
  explicit CatacombBuilder(const CatacombOptions& options)
      : options_(options), store_(options.out / "local_maps", options.store), cache_(store_),
        random_(options.injection_seed) {}

  Result<CatacombResult> Run() {
    if (Status created = store_.Create(); !created.ok()) return created.error();
    if (Status tracked = Track(); !tracked.ok()) return tracked.error();
    if (Status trajectories = WriteMapTrajectories(); !trajectories.ok()) return trajectories.error();
    BuildChain();
    const Clock::time_point start = Clock::now();
    for (int current = 0; current < static_cast<int>(result_.maps.size()); ++current) {
      if (Status closed = CloseLoops(current); !closed.ok()) return closed.error();
    }
    result_.candidate_seconds = SecondsSince(start) - validation_seconds_;
    if (Status edited = ApplyEdits(); !edited.ok()) return edited.error();
    Solve();
    PlaceRevolutions();
    return std::move(result_);
  }

 private:
  // Step 1.
  Status Track() {
    NicpDriveOptions drive = options_.drive;
    if (drive.local_map_distance_m <= 0.0) drive.local_map_distance_m = 5.0;
    drive.frame_to_model = true;
    drive.build_map = false;
    drive.model_every = 0;  // the nicp build's model.ply sample: the local maps hold the points
    Status written = Status::Ok();
    drive.on_local_map = [&](const TrackedLocalMap& map) {
      const int index = static_cast<int>(tracked_.size());
      if (written.ok()) written = store_.WritePoints(index, map.points, map.world_T_sensor_at_start);
      tracked_.push_back({map.world_T_sensor_at_start, map.first_revolution, map.last_revolution, map.ends_in_failure});
    };
    const Clock::time_point start = Clock::now();
    auto drove = TrackDriveByNicp(drive);
    if (!drove.ok()) return drove.error();
    if (!written.ok()) return written.error();
    result_.drive = std::move(*drove);
    result_.tracking_seconds = SecondsSince(start);
    if (options_.break_at_map) {
      if (Status broken = BreakChain(*options_.break_at_map); !broken.ok()) return broken;
    }
    DescribeMaps();
    return Status::Ok();
  }

  // The injected break: maps from `at` on, and their revolutions, moved about map at's frame.
  Status BreakChain(int at) {
    if (at < 1 || at >= static_cast<int>(tracked_.size())) {
      return MakeError("--break-chain " + std::to_string(at) + ": the drive has local maps 1 to " +
                       std::to_string(tracked_.size() - 1) + " to break before");
    }
    const Eigen::Isometry3d pivot = tracked_[static_cast<std::size_t>(at)].world_T_map;
    const Eigen::Isometry3d move = pivot * options_.break_error * pivot.inverse();
    for (std::size_t i = static_cast<std::size_t>(at); i < tracked_.size(); ++i) tracked_[i].world_T_map = move * tracked_[i].world_T_map;
    auto& trajectory = result_.drive.trajectory;
    for (std::size_t k = static_cast<std::size_t>(tracked_[static_cast<std::size_t>(at)].first_revolution); k < trajectory.size(); ++k) {
      trajectory[k].world_T_body = move * trajectory[k].world_T_body;
    }
    tracked_[static_cast<std::size_t>(at) - 1].ends_in_failure = true;
    return Status::Ok();
  }

  // The loop closer's view of each map: its tracked pose, internal trajectory, path start.
  void DescribeMaps() {
    const auto& trajectory = result_.drive.trajectory;
    std::vector<Eigen::Isometry3d> poses;
    for (const auto& pose : trajectory) poses.push_back(pose.world_T_body);
    const std::vector<double> path = loops::ArcLengths(poses);
    for (const TrackedMap& map : tracked_) {
      loops::LocalMapTrajectory described;
      described.world_T_map = map.world_T_map;
      described.path_start_m = path[static_cast<std::size_t>(map.first_revolution)];
      for (int k = map.first_revolution; k <= map.last_revolution; ++k) {
        described.map_T_pose.push_back(map.world_T_map.inverse() * trajectory[static_cast<std::size_t>(k)].world_T_body);
      }
      result_.maps.push_back(std::move(described));
      result_.first_revolution.push_back(map.first_revolution);
      result_.last_revolution.push_back(map.last_revolution);
    }
  }

  // Each map's internal trajectory (DescribeMaps') with the revolutions' stamps.
  Status WriteMapTrajectories() const {
    for (std::size_t i = 0; i < result_.maps.size(); ++i) {
      std::vector<hal::trajectory::StampedPose> poses;
      const auto& map_T_pose = result_.maps[i].map_T_pose;
      for (std::size_t k = 0; k < map_T_pose.size(); ++k) {
        poses.push_back({result_.drive.trajectory[static_cast<std::size_t>(tracked_[i].first_revolution) + k].time_ns, map_T_pose[k]});
      }
      if (Status s = store_.WriteTrajectory(static_cast<int>(i), poses); !s.ok()) return s;
    }
    return Status::Ok();
  }

  // Step 2.
  void BuildChain() {
    for (const TrackedMap& map : tracked_) result_.graph.AddNode(map.world_T_map);
    const FactorSigma& tracking = options_.drive.planar ? options_.planar_tracking : options_.tracking;
    for (std::size_t i = 0; i + 1 < tracked_.size(); ++i) {
      tie_failed_.push_back(tracked_[i].ends_in_failure);
      graph::Se3BetweenFactor factor;
      factor.from = i;
      factor.to = i + 1;
      factor.measurement = tracked_[i].world_T_map.inverse() * tracked_[i + 1].world_T_map;
      factor.information = InformationOf(tie_failed_[i] ? options_.odometry : tracking);
      result_.graph.betweens.push_back(factor);
    }
  }

  // Step 3 for one map: its candidates (with any injected), validated; the best accepted
  // per past map kept for the graph.
  Status CloseLoops(int current) {
    std::vector<loops::LoopCandidate> candidates;
    if (options_.distance_candidates) candidates = loops::DistanceCandidates(result_.maps, current, options_.candidates);
    if (options_.shape_candidates) {
      for (auto& c : loops::TrajectoryShapeCandidates(result_.maps, current, options_.candidates)) candidates.push_back(c);
    }
    const std::size_t real = candidates.size();
    InjectFalse(current, real, candidates);
    std::map<int, std::size_t> best;  // past map -> record
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      auto record = Validate(candidates[i], i >= real);
      if (!record.ok()) return record.error();
      result_.closures.push_back(std::move(*record));
      const ClosureRecord& r = result_.closures.back();
      if (!r.validation.accepted) continue;
      auto [it, inserted] = best.emplace(r.candidate.reference, result_.closures.size() - 1);
      if (!inserted && result_.closures[it->second].validation.inlier_share < r.validation.inlier_share) {
        it->second = result_.closures.size() - 1;
      }
    }
    for (const auto& [reference, record] : best) accepted_.push_back(record);
    return Status::Ok();
  }

  Result<ClosureRecord> Validate(const loops::LoopCandidate& candidate, bool injected) {
    const Clock::time_point start = Clock::now();
    // The newest map first: a read evicts the lowest index, never the newest.
    auto current = cache_.Get(candidate.current);
    if (!current.ok()) return current.error();
    auto reference = cache_.Get(candidate.reference);
    if (!reference.ok()) return reference.error();
    ClosureRecord record;
    record.candidate = candidate;
    record.injected = injected;
    record.validation = loops::ValidateClosure(**reference, **current, candidate.reference_T_current, options_.validation);
    if (record.validation.accepted && options_.alias_neighbours > 0 &&
        (options_.alias_everywhere || loops::ChainCrossesFailure(tie_failed_, candidate.reference, candidate.current))) {
      auto alias = FindAlias(candidate, record.validation);
      if (!alias.ok()) return alias.error();
      record.validation.reason = std::move(*alias);
      record.validation.accepted = record.validation.reason.empty();
    }
    const double seconds = SecondsSince(start);
    validation_seconds_ += seconds;
    result_.validation_ms.push_back(1e3 * seconds);
    return record;
  }

  // The current map tried on the reference's neighbours, nearest first, one read at a time:
  // the cache never evicts the newest map, and the reference is not needed again.
  Result<std::string> FindAlias(const loops::LoopCandidate& candidate, const loops::ClosureValidation& fit) {
    const auto& maps = result_.maps;
    const auto& reference = maps[static_cast<std::size_t>(candidate.reference)];
    const auto& current = maps[static_cast<std::size_t>(candidate.current)];
    for (int step = 1; step <= options_.alias_neighbours; ++step) {
      for (const int k : {candidate.reference - step, candidate.reference + step}) {
        if (k < 0 || k >= candidate.current) continue;
        const auto& neighbour = maps[static_cast<std::size_t>(k)];
        if (current.path_start_m - neighbour.path_start_m < options_.candidates.min_path_separation_m) continue;
        auto neighbour_points = cache_.Get(k);
        if (!neighbour_points.ok()) return neighbour_points.error();
        auto current_points = cache_.Get(candidate.current);
        if (!current_points.ok()) return current_points.error();
        const loops::AliasNeighbour probe{k, *neighbour_points,
                                          reference.world_T_map.inverse() * neighbour.world_T_map};
        std::string reason = loops::FindAlias(**current_points, fit, probe, options_.validation);
        if (!reason.empty()) return reason;
      }
    }
    return std::string();
  }

  // Injected false candidates: enough that they make injected_false_share of all tried.
  void InjectFalse(int current, std::size_t real, std::vector<loops::LoopCandidate>& candidates) {
    const double share = options_.injected_false_share;
    if (share <= 0.0 || share >= 1.0) return;
    injection_due_ += static_cast<double>(real) * share / (1.0 - share);
    const auto& newest = result_.maps[static_cast<std::size_t>(current)];
    std::vector<int> distant;
    for (int r = 0; r < current; ++r) {
      const auto& past = result_.maps[static_cast<std::size_t>(r)];
      const double apart = (past.world_T_map.translation() - newest.world_T_map.translation()).norm();
      if (newest.path_start_m - past.path_start_m >= options_.candidates.min_path_separation_m && apart > 30.0) {
        distant.push_back(r);
      }
    }
    while (injection_due_ >= 1.0 && !distant.empty()) {
      injection_due_ -= 1.0;
      std::uniform_int_distribution<std::size_t> pick(0, distant.size() - 1);
      loops::LoopCandidate false_candidate;
      false_candidate.reference = distant[pick(random_)];
      false_candidate.current = current;
      false_candidate.reference_T_current = Eigen::Isometry3d::Identity();
      candidates.push_back(false_candidate);
    }
  }

  // Step 4.
  Status ApplyEdits() {
    const int maps = static_cast<int>(result_.maps.size());
    auto out_of_range = [&](int reference, int current) {
      return reference >= maps || current >= maps || reference == current;
    };
    for (const auto& removal : options_.edits.removals) {
      const int reference = removal.first, current = removal.second;  // lambdas cannot capture bindings in clang 14
      if (out_of_range(reference, current)) return MakeError(EditError("remove", reference, current));
      std::erase_if(accepted_, [&](std::size_t record) {
        const auto& c = result_.closures[record].candidate;
        return c.reference == reference && c.current == current;
      });
    }
    for (const auto& addition : options_.edits.additions) {
      if (out_of_range(addition.reference, addition.current)) {
        return MakeError(EditError("add", addition.reference, addition.current));
      }
      ClosureRecord record;
      record.candidate.reference = addition.reference;
      record.candidate.current = addition.current;
      record.candidate.reference_T_current = addition.reference_T_current;
      record.validation.accepted = true;
      record.validation.result.target_T_source = addition.reference_T_current;
      record.edited = true;
      result_.closures.push_back(record);
      accepted_.push_back(result_.closures.size() - 1);
    }
    return Status::Ok();
  }

  std::string EditError(const char* verb, int reference, int current) const {
    return "closure edit " + std::string(verb) + " " + std::to_string(reference) + " " + std::to_string(current) +
           ": the drive has local maps 0 to " + std::to_string(result_.maps.size() - 1) + " (and a closure joins two)";
  }

  // Step 5.
  void Solve() {
    std::vector<std::size_t> factors;
    for (const std::size_t record : accepted_) {
      ClosureRecord& r = result_.closures[record];
      graph::Se3BetweenFactor factor;
      factor.from = static_cast<std::size_t>(r.candidate.reference);
      factor.to = static_cast<std::size_t>(r.candidate.current);
      factor.measurement = r.validation.result.target_T_source;
      factor.information = InformationOf(options_.closure);
      r.factor = result_.graph.betweens.size();
      factors.push_back(result_.graph.betweens.size());
      result_.graph.betweens.push_back(factor);
    }
    result_.solve = loops::OptimizeWithRobustClosures(result_.graph, factors, options_.robust);
    for (std::size_t i = 0; i < accepted_.size(); ++i) {
      ClosureRecord& r = result_.closures[accepted_[i]];
      r.scale = result_.solve.scales[i];
      r.kept = result_.solve.kept[i];
    }
    JudgeFailureTies();
  }

  // Step 5, second half: the ties across failed registrations (or the injected break)
  // judged against the kept closures (loops::JudgeWeakTies).
  void JudgeFailureTies() {
    std::vector<std::size_t> ties, closures;
    for (std::size_t i = 0; i < tie_failed_.size(); ++i) {
      if (tie_failed_[i]) ties.push_back(i);  // the chain's factor i joins maps i and i + 1
    }
    for (const std::size_t record : accepted_) closures.push_back(*result_.closures[record].factor);
    result_.failure_tie_scales =
        loops::JudgeWeakTies(result_.graph, ties, closures, result_.solve.kept, options_.robust, result_.solve);
  }

  // Step 6: each revolution moved with the map that holds it.
  void PlaceRevolutions() {
    const auto& tracked = result_.drive.trajectory;
    for (std::size_t i = 0; i < tracked_.size(); ++i) {
      const Eigen::Isometry3d correction = result_.graph.nodes[i].estimate * tracked_[i].world_T_map.inverse();
      const int end = i + 1 < tracked_.size() ? tracked_[i + 1].first_revolution : static_cast<int>(tracked.size());
      for (int k = tracked_[i].first_revolution; k < end; ++k) {
        const auto& pose = tracked[static_cast<std::size_t>(k)];
        result_.trajectory.push_back({pose.time_ns, correction * pose.world_T_body});
      }
    }
  }

  const CatacombOptions& options_;
  loops::LocalMapStore store_;
  MapCache cache_;
  std::mt19937 random_;
  CatacombResult result_;
  std::vector<TrackedMap> tracked_;
  std::vector<std::size_t> accepted_;  // records that become closures
  std::vector<bool> tie_failed_;       // per tie of the chain (BuildChain): across a failed registration
  double injection_due_ = 0.0;
  double validation_seconds_ = 0.0;
};

}  // namespace

Result<CatacombResult> BuildCatacomb(const CatacombOptions& options) { return CatacombBuilder(options).Run(); }

Result<std::optional<maps::ClassGrid>> GridCatacomb(const CatacombOptions& options, const CatacombResult& result) {
  return GridCaptureAtPoses(options.drive.capture, options.drive.grid, options.drive.stream, options.drive.accumulation,
                            result.trajectory);
}

}  // namespace flat2d::localization::tools
