// The usage text of flat2d-map build --mode catacomb (catacomb_command.hpp), apart from the
// command's parsing and output.
#include "localization/tools/catacomb_command.hpp"

namespace flat2d::localization::tools {

const char* const kCatacombUsage = R"(
build --mode catacomb DRIVE --out DIR: local-map 3D SLAM of a Velodyne capture or a KITTI
sequence directory (thesis 6.3). Each revolution is tracked by NICP against the merged
model of the current local map (as build --mode nicp DRIVE); every 5 m, or where a
registration fails, the map is closed and written and a new one begins. Loop closures
between local maps are proposed by distance and by trajectory shape, validated by NICP
between the two maps (KD-tree, alpha = 1/3) and enter the SE(3) graph of the maps behind
dynamic covariance scaling. Writes:
  DIR/graph.g2o          VERTEX_SE3:QUAT per local map (optimized), EDGE_SE3:QUAT per tie
  DIR/trajectory.tum     world_T_vehicle per revolution from the optimized graph
  DIR/tracking.tum       the same before the graph: the tracking alone
  DIR/odometry.tum       with --can: the CAN odometry open loop from the same first pose
  DIR/map.ply            the local maps' points and normals at their optimized poses
  DIR/closures.txt       every candidate: maps, source, verdict, inliers, chi2, DCS scale
  DIR/local_maps/        map_NNNN.ply (points and normals, map frame), map_NNNN.tum
  DIR/truth.tum          a KITTI sequence with poses.txt and calib.txt: its truth,
                         world_T_vehicle per scan from the first scan's vehicle frame (also
                         the --truth below)
  DIR/map.f2m, map.png   the 2D prior map gridded at the optimized poses (captures only)
Options of build --mode nicp DRIVE: --can LOG --dbc DBC --odometry CONFIG, --config FILE,
--anchor FILE.tum, --method M, --iterations N, --max-frames N, --min-inlier-share S,
--no-deskew, --inverse-depth-weights, --planar, --ground-clearance M, --ground-range M, --no-map, --json.
Also:
  --local-map-distance M  a new local map after M metres of travel (default 5)
  --local-map-angle RAD   ... or once the sensor has turned RAD from the map's first
                          revolution (default 0: no such cut)
  --local-map-overlap S   ... or when a revolution's NICP inliers are less than share S of its
                          points with normals (default 0: none; below --min-inlier-share
                          the registration fails, which always cuts)
  --continuous-tracking   track against one merged model across the cuts (each local map
                          merges its revolutions into its own model besides) instead of
                          starting each map's tracking afresh (thesis 6.3)
  --pyramid S,S,...       the tracker's levels, as in build --mode nicp DRIVE: 8,4,2 is the
                          thesis' 1/8, 1/4, 1/2 of the columns (6.3.1), 8,4,2,1 adds the full
                          image, --pyramid-iterations 3 at each (default 1: one level at full
                          resolution, --iterations 10; docs/benchmarks.md)
  --range-merge-weights   merge a local map's points weighted by w = 1/range (thesis Eq. 6.4,
                          6.11-6.12) instead of 1/range^2 (Eq. 5.22; the default, better on
                          the simulated campus: docs/benchmarks.md)
  --ambiguity-shift M     refuse a closure whose fit NICP also finds, as good, from M metres
                          along its least constrained direction (a road or corridor fits
                          anywhere along itself; default 0: no such test; docs/benchmarks.md)
  --alias-neighbours N    refuse a closure when the current map fits one of the N past maps on
                          each side of its reference (along the trajectory) as well, somewhere
                          else: a place whose look repeats. Only where the chain between the
                          two maps crosses a failed registration (or the injected break),
                          whose guess may be off by a map or more (default 1; 0: no such
                          test; docs/benchmarks.md)
  --alias-everywhere      the alias test on every closure NICP accepts
  --no-loops              no loop closing: the chain of local maps alone
  --no-distance-candidates, --no-shape-candidates
                          leave out one kind of candidate
  --closures FILE         closure edits: "add REF CUR x y z qx qy qz qw" (reference_T_current),
                          "remove REF CUR", one per line, # comments
  --inject-false SHARE    add false candidates, SHARE of all tried (0.2: one in five), each
                          claiming the current map lies on a distant past one
  --break-chain MAP       move the tracked poses from local map MAP on by 1 m sideways and 5 deg
                          of yaw, as a failed registration with a bad guess would (the tie
                          into MAP gets the odometry's sigma): what loop closing must repair
  --truth FILE.tum        the drive's 3D truth (flat2d-sim's truth.tum; a KITTI sequence's
                          own by default): the JSON adds the closures' precision and recall
                          against it
The JSON has build --mode nicp DRIVE's tracking keys (frames, failures, frame_ms_p50,
frame_ms_p95, registration_ms_p50, sensor, tracked_distance_m; with --anchor the drift
keys of the optimized trajectory) and local_maps, tracking_failures_cut, cuts_distance,
cuts_angle, cuts_overlap, cuts_failure (why each local map but the last was closed),
failure_ties, failure_ties_overruled (ties across failed registrations, and those the
kept closures overruled: DCS scale below 0.5), candidates, candidates_distance,
candidates_shape, candidates_injected, validated, accepted,
closures_kept, injected_accepted, injected_kept, edits_added, edits_removed,
candidate_seconds, validation_ms_p50, solve_seconds, solve_rounds, graph_cost_initial,
graph_cost_final, tracking_seconds, grid_seconds; with --truth: revisits,
informative_revisits, closures_correct, closure_precision, closure_recall,
local_map_rpe_mean_m, local_map_rpe_mean_rad (between consecutive local maps, optimized),
tracking_local_map_rpe_mean_m, tracking_local_map_rpe_mean_rad (before the graph).
)";

}  // namespace flat2d::localization::tools
