// `flat2d-map build --mode nicp DRIVE`: a Velodyne drive tracked by NICP (thesis 5.1, 5.3)
// revolution to merged model (5.1.4) or to keyframe revolution, and the 2D prior map
// gridded at the poses it found.
//
// Steps: (1) every complete revolution of the capture (VelodyneStream) deskewed into the
// sensor frame of its first fan (revolution_cloud.hpp) and made an organized range frame of
// the identified model (spherical projection, surface statistics over R = 0.3 m); (2) each
// registered to the merged model of the revolutions before, seen from the previous pose, and
// merged into it (or to the last keyframe, a revolution kept until the sensor is 1 m or
// 0.1 rad from it), from a guess: the CAN odometry's motion since the previous revolution
// when a CAN log is given, else the previous motion (constant velocity); a failed
// registration keeps the guess and is counted; (3) the poses chained in the sensor frame,
// world_T_vehicle = world_T_sensor sensor_T_vehicle, the first revolution at the anchor's
// pose, else the odometry's, else the origin; (4) the capture gridded again at those poses
// (grid_run.hpp's accumulation, the --pcap build's second pass) into the map's mosaic.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/evaluation/relations.hpp"
#include "localization/tools/drift.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/registration/nicp_options.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/grid/grid_accumulator.hpp"
#include "maps/grid/structure_grid_options.pb.h"
#include "maps/range3d/range_frame.hpp"
#include "maps/range3d/surfel_model.hpp"

namespace flat2d::localization::tools {

// A local map as the tracker closes it (thesis 6.3, build --mode catacomb): the merged
// model's points in the world frame of the tracking, and the revolutions it was built from.
struct TrackedLocalMap {
  const maps::range3d::SurfelCloud& points;    // world frame (the tracking's)
  Eigen::Isometry3d world_T_sensor_at_start;   // the map's frame: its first revolution's sensor
  int first_revolution = 0;                    // indices into NicpDriveResult::trajectory,
  int last_revolution = 0;                     // both included
  bool ends_in_failure = false;  // the next map starts at a revolution that failed to register
};

struct NicpDriveOptions {
  // A Velodyne capture (.pcap, .pcapng), or a KITTI sequence directory
  // (hal/cloud/kitti_sequence.hpp): its scans tracked as they are stored, no map gridded.
  std::filesystem::path capture;
  // CAN odometry (all three or none): the registration guess and the deskewing motion.
  std::optional<std::filesystem::path> can_log, dbc, odometry_config;
  maps::StructureGridOptions grid;  // the sensor's mounting and the map's grids
  hal::velodyne::VelodyneStreamOptions stream;
  registration::RegistrationMethod method = registration::RegistrationMethod::kNicp;
  registration::NicpOptions nicp;
  maps::range3d::RangeFrameOptions frames;
  bool deskew = true;       // move each fan by the motion since the revolution's first fan
  // Points lower than this above the vehicle's ground plane stay out of the range frames
  // (negative: none). Beyond a few metres a ground ring lies alone within R, its "surface"
  // is a line whose normal is any direction across it, and the pairs of rings that moved
  // with the sensor pull every motion towards standing still: on the office drive's first
  // 8 s (HDL-32E) NICP fell 1.9 % short with the ground, 0.13 % without.
  double ground_clearance_m = 0.2;
  // ... except within this horizontal range of the sensor, where rings lie closer than R
  // and the ground is a plane that holds height, roll and pitch (an HDL-32E at 1.9 m: rings
  // r^2 / 1.9 m x 1.33 deg apart, 0.3 m at r = 4.9 m; a VLP-16's 2 deg, at 4.0 m).
  double ground_range_m = 4.0;
  int max_revolutions = 0;  // 0: every complete revolution
  // Without the model, each revolution registers to the last keyframe, a revolution kept
  // until the sensor is this far from it: fewer links in the chain than revolution to
  // revolution (0: every revolution is a keyframe). On the simulated office drive (428 m at 1.2 m/s) 1 m cut the
  // drift from 0.20 % to 0.009 % of the distance, 0.5 m to 0.021 %.
  double keyframe_distance_m = 1.0;
  double keyframe_angle_rad = 0.1;
  // Each revolution registered to the merged model of the ones before (the default;
  // registration/model_tracker.hpp, thesis 5.1.4) and merged into it, the model keeping the
  // latest max_points points, a local map that follows the vehicle. False: to the last
  // keyframe. On the simulated office and campus drives the model drifted 0.0014 % and
  // 0.0095 % of the distance, keyframes 0.009 % and 0.067 % (docs/benchmarks.md).
  bool frame_to_model = true;
  maps::range3d::SurfelModelOptions model{0.05F, 0.01F, 0.5F, 50.0F, 1'000'000, 0.02F, 1e-3F};
  // Local maps (frame_to_model only; thesis 6.3): above 0, once the sensor has travelled this
  // far since the model began, or when a registration fails, the model goes to on_local_map
  // and a new one starts from the current revolution. The last one goes at the drive's end.
  double local_map_distance_m = 0.0;
  // Our cuts besides the thesis' two (local_map_distance_m above 0 only; 0: none): once the
  // sensor has turned this far from the map's first revolution, or when a revolution's
  // inliers are less than this share of its points with normals (the view has moved off the
  // model: with continuous tracking, the model across the cuts).
  double local_map_angle_rad = 0.0;
  double local_map_min_overlap = 0.0;
  std::function<void(const TrackedLocalMap&)> on_local_map;
  // False (thesis 6.3): each local map is tracked against its own model, started afresh at
  // the cut. True: tracking runs on against the one merged model across cuts and each
  // local map merges its revolutions into a model of its own: the cut costs the tracking
  // nothing (a fresh model holds one revolution), at a second merge per revolution.
  bool continuous_tracking = false;
  // The model tracker's pyramid (thesis 6.3.1: 1/8, 1/4, 1/2 of the image): the spherical
  // view's columns divided by each, coarse to fine, every row kept (an HDL-32E's 32 rows
  // cannot be halved three times); iterations_per_level at each. {1}: one level at full
  // resolution, nicp.iterations there (the default).
  std::vector<int> lidar_pyramid{1};
  int pyramid_iterations = 3;
  // A revolution whose inliers are fewer than this share of its points with normals has
  // failed to register (the tracker's depth-camera 0.3 is too strict here). On the
  // simulated campus lap the shares run 0.24-0.57 (p1 0.31): at 0.3, 9 revolutions
  // failed, each of them within 2.2 mm and 0.006 deg of the truth when kept, and every
  // failure cuts the chain to the odometry's guess (docs/benchmarks.md).
  float min_inlier_share = 0.2F;
  // Keep the vehicle on the ground plane after every registration (height, roll and pitch
  // zero): flat2d's ground vehicles on flat ground. Without it a pitch bias of a few tenths
  // of a degree climbs tens of metres over a kilometre.
  bool planar = false;
  // The first revolution's vehicle pose (a truth or GNSS track in the map frame). Empty: the
  // odometry's pose then, or the origin without odometry.
  std::vector<evaluation::TimedPose> anchor;
  bool build_map = true;
  maps::AccumulationOptions accumulation;
  // The PLY model: the points of every model_every-th revolution, every model_stride-th of them.
  int model_every = 10;
  int model_stride = 16;
};

// Why local maps were closed (the last, at the drive's end, is not counted).
struct LocalMapCuts {
  int distance = 0, angle = 0, overlap = 0, failure = 0;
};

struct NicpDriveResult {
  // world_T_vehicle at each tracked revolution's first fan.
  std::vector<hal::trajectory::StampedPose> trajectory;
  // The CAN odometry dead-reckoned open loop, at the same stamps from the same first pose
  // (empty without a CAN log).
  std::vector<hal::trajectory::StampedPose> odometry;
  std::vector<Eigen::Vector3f> model_points, model_normals;
  // A KITTI sequence's poses.txt and calib.txt: world_T_vehicle per tracked scan, in the
  // tracking's world (the first scan's vehicle frame without an anchor). Empty otherwise.
  std::vector<hal::trajectory::StampedPose> truth;
  std::optional<maps::ClassGrid> mosaic;  // none when not asked for or nothing was gridded
  std::string sensor;                     // the range frames' model ("hdl32e", ...)
  int frames = 0;                         // revolutions tracked
  int failures = 0;                       // registrations that failed (the guess kept)
  int guesses_without_odometry = 0;       // pairs outside the CAN log's time (constant velocity)
  LocalMapCuts local_map_cuts;
  std::vector<double> frame_ms;         // per registered revolution: its statistics + the registration
  std::vector<double> registration_ms;  // the registration alone
  std::vector<double> load_ms;          // the revolution's deskewed cloud
  double grid_seconds = 0.0;            // the map's gridding pass
};

// An error names the file when the capture, the CAN log, the DBC or the odometry
// configuration cannot be read, the capture's model is unsupported, or it holds no complete
// revolution.
Result<NicpDriveResult> TrackDriveByNicp(const NicpDriveOptions& options);

}  // namespace flat2d::localization::tools
