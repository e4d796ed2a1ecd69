// `flat2d-map features`: the 3D line and plane features (thesis 8.1,
// maps/features3d/feature_extractor.hpp) of the revolutions of a Velodyne capture, or of
// one cloud file (PCD, KITTI .bin), optionally judged against a simulator run's truth.
//
// Captures: every complete revolution (or only --revolution N) made a cloud in the sensor
// frame of its first fan (revolution_cloud.hpp), deskewed by the truth trajectory when one
// is given; gravity in the sensor frame from the mounting of the structure-grid config.
// Cloud files: the sensor's z is taken as up (KITTI's HDL-64E, a level Velodyne).
// With a world and its truth trajectory (flat2d-sim's truth.tum), each revolution's features
// are judged by localization/evaluation/feature_accuracy.hpp at the truth pose.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/common/time.hpp"
#include "hal/sim/scene.pb.h"
#include "hal/trajectory/tum_file.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "localization/evaluation/feature_accuracy.hpp"
#include "maps/features3d/feature_extractor.hpp"
#include "maps/features3d/feature_options.pb.h"

namespace flat2d::localization::tools {

struct FeaturesRunOptions {
  std::filesystem::path input;
  int revolution = -1;  // captures: only this complete revolution (0-based); -1: all
  maps::features3d::FeatureExtractionOptions extraction;
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();  // captures' gravity
  hal::velodyne::VelodyneStreamOptions stream;
  // Judging (captures of simulator runs): the world and the vehicle's truth trajectory.
  std::optional<hal::sim::SceneDescription> world;
  std::vector<hal::trajectory::StampedPose> truth;
  double world_time_offset_s = 0.0;  // the drive's (flat2d-sim --drive): where traffic is
  evaluation::FeatureAccuracyOptions accuracy;
};

struct RevolutionFeatures {
  int index = 0;          // complete revolutions counted from 0; 0 for a cloud file
  TimeNs stamp_ns = 0;
  std::string sensor;     // vlp16, hdl32e, vlp32c, kitti64
  const maps::features3d::FeatureSet* features = nullptr;
  const maps::features3d::FeatureExtractor* extractor = nullptr;  // stats, image, clusters
  std::optional<evaluation::RevolutionAccuracy> accuracy;
};

// Called once per revolution (or cloud); the pointers live until it returns.
using FeaturesHandler = std::function<void(const RevolutionFeatures&)>;

// Errors: the input unreadable or of no supported kind, no complete revolution, a truth that
// does not cover a revolution, a sensor model without a laser table.
Status RunFeatures(const FeaturesRunOptions& options, const FeaturesHandler& handler);

}  // namespace flat2d::localization::tools
