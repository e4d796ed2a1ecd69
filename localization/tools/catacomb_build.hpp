// `flat2d-map build --mode catacomb DRIVE`: local-map 3D SLAM of a Velodyne drive (thesis
// 6.3), ending in a 2D prior map.
//
// Steps:
//   1. Tracking (nicp_drive_build.hpp, each revolution against the merged model): every
//      local_map_distance_m of travel (5 m, 6.3), or where a registration fails, the model
//      becomes a local map and a new one starts from the current revolution. A map's points
//      go to disk as it closes (loops/local_map_store.hpp); its internal trajectory stays in
//      memory as poses only.
//   2. The SE(3) graph (6.3.3): a node per local map at its tracked pose (its frame is its
//      first revolution's sensor); consecutive maps tied by the tracking's relative pose, or
//      by the odometry's guess where a failed registration separates them (weaker).
//   3. Loop closing (6.3.2), map by map in driving order as it would run online: candidates
//      by distance and by trajectory shape (loops/loop_candidates.hpp), each validated by
//      NICP between the two maps read back from disk (loops/closure_validation.hpp); the
//      best accepted per pair of maps becomes a closure. Optionally, false candidates are
//      injected (the acceptance test of the validation and the robust kernel).
//   4. Closure edits from a file (the refiner of 6.3.4, loops/closure_edits.hpp): add, remove.
//   5. The graph solved with the closures behind dynamic covariance scaling
//      (loops/robust_closures.hpp); then the ties across failed registrations behind the
//      kernel against the kept closures: the odometry's guess there may be what the
//      closures must overrule (thesis Fig. 6.7).
//   6. Each revolution's pose from its map's optimized pose; the capture gridded again at
//      those poses into the prior map's mosaic.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/graph/se3_pose_graph.hpp"
#include "localization/loops/closure_edits.hpp"
#include "localization/loops/closure_validation.hpp"
#include "localization/loops/local_map_store.hpp"
#include "localization/loops/local_map_trajectory.hpp"
#include "localization/loops/loop_candidates.hpp"
#include "localization/loops/robust_closures.hpp"
#include "localization/tools/nicp_drive_build.hpp"

namespace flat2d::localization::tools {

// Standard deviations of the graph's factors: translation (m) and rotation (rad), isotropic.
struct FactorSigma {
  double translation_m = 0.0;
  double rotation_rad = 0.0;
};

struct CatacombOptions {
  NicpDriveOptions drive;         // its local_map_distance_m is step 1's (5 m unless set)
  std::filesystem::path out;      // the local maps go to out / "local_maps"
  loops::LocalMapStoreOptions store;
  bool distance_candidates = true;
  bool shape_candidates = true;
  loops::LoopCandidateOptions candidates = DefaultCandidates();
  loops::ClosureValidationOptions validation;
  // Past maps on each side of an accepted closure's reference, along the trajectory, that the
  // current map is also tried on (loops::FindAlias); 0: none. Only for closures whose chain
  // from the reference to the current map crosses a failed registration (or the injected
  // break), unless alias_everywhere: elsewhere the tracked guess is within centimetres and a
  // repeating place (a straight road) a map length off cannot be mistaken for it, while the
  // test would refuse most right closures there (docs/benchmarks.md, "An alias test for
  // closures": on the unbroken campus, 7 of 10). Across a failure, the odometry's guess
  // can be metres off along such a road: the broken campus' false closures.
  int alias_neighbours = 1;
  bool alias_everywhere = false;
  loops::RobustClosureOptions robust;
  // The tracking between consecutive maps: 5 m of merged-model tracking drifts about
  // 0.01-0.1 % in the plane (docs/benchmarks.md), a few mm; the sigmas allow for the
  // height and tilt, which drift more.
  FactorSigma tracking{0.02, 0.002};
  // With drive.planar the tracker holds roll and pitch, so a tie's rotation is the yaw's,
  // which drifts far less: 6e-5 rad per map on the simulated campus lap against 0.0019 rad
  // in 3D in the office. At 0.002 the lap's 213 ties let 12 right closures (0.36 deg RMS
  // off) bend it: ATE 0.139 m against 0.080 m tracking alone, map recall 0.31; at 0.0002,
  // 0.083 m and 0.92 (docs/benchmarks.md, "Local-map SLAM").
  FactorSigma planar_tracking{0.02, 0.0002};
  FactorSigma odometry{0.2, 0.02};  // across a failed registration: the CAN odometry's guess
  FactorSigma closure{0.05, 0.005};
  loops::ClosureEdits edits;
  // Injected false candidates, as a share of all candidates tried (0.2: one in five): each
  // claims the current map lies where a random distant past map is, with the past map's
  // heading (what a false trajectory-shape match proposes).
  double injected_false_share = 0.0;
  std::uint32_t injection_seed = 1;
  // A broken chain (thesis Fig. 6.7): from this map on, the tracked poses are moved by
  // break_error about the map's frame, as if its registration had failed and the guess been
  // that far off; the tie into it gets the odometry's sigma. Closures must repair it.
  std::optional<int> break_at_map;
  Eigen::Isometry3d break_error = DefaultBreak();

  static Eigen::Isometry3d DefaultBreak() {  // the acceptance test's 1 m / 5 deg
    Eigen::Isometry3d error(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
    error.translation() = Eigen::Vector3d(0.0, 1.0, 0.0);
    return error;
  }

  static loops::LoopCandidateOptions DefaultCandidates() {
    loops::LoopCandidateOptions o;
    // The drift bound (KITTI 00: candidate precision 0.04 without, 0.46 at 0.05), wider here
    // for the chain broken by 1 m / 5 deg that closures must repair; NICP validation and
    // the robust kernel stand behind it.
    o.drift_fraction = 0.1;
    return o;
  }
};

// One candidate and what validation made of it.
struct ClosureRecord {
  loops::LoopCandidate candidate;  // reference_T_current: the guess
  loops::ClosureValidation validation;
  bool injected = false;           // an injected false candidate
  bool edited = false;             // added by the closure edits file
  // Of the accepted ones: the factor's index in the graph and its final DCS scale.
  std::optional<std::size_t> factor;
  double scale = 0.0;
  bool kept = false;
};

struct CatacombResult {
  NicpDriveResult drive;  // drive.trajectory: the tracking alone, before the graph
  std::vector<loops::LocalMapTrajectory> maps;
  std::vector<int> first_revolution;  // per map (its last is the next map's first, or before it)
  std::vector<int> last_revolution;
  graph::Se3PoseGraph graph;          // optimized
  std::vector<ClosureRecord> closures;  // every candidate validated, in the order tried
  loops::RobustClosureResult solve;  // its scales: the accepted closures' (rounds and time include the ties')
  // Per tie across a failed registration (or the injected break), in driving order: its final
  // DCS scale against the kept closures (below 0.5: they overruled the odometry's guess; 1
  // when no closure was kept).
  std::vector<double> failure_tie_scales;
  std::vector<hal::trajectory::StampedPose> trajectory;  // world_T_vehicle per revolution, optimized
  double candidate_seconds = 0.0;
  std::vector<double> validation_ms;  // per candidate validated (reading both maps included)
  double tracking_seconds = 0.0;
};

// Errors: those of TrackDriveByNicp, a local map that cannot be written or read, and a
// closure edit that names a map the drive does not have.
Result<CatacombResult> BuildCatacomb(const CatacombOptions& options);

// Step 6's mosaic at result.trajectory (none when nothing was gridded).
Result<std::optional<maps::ClassGrid>> GridCatacomb(const CatacombOptions& options, const CatacombResult& result);

}  // namespace flat2d::localization::tools
