// A prior map and a localization drive for the daemon's tests: the simulator's `occluders`
// world (a walled 57 x 30 m room with a row of boxes), its mapping drive built into a map
// as `flat2d-map build` does (anchored to the truth), and drive 2 (40 m east along the
// row) to localize.
//
// Made once per process in a scratch folder removed at exit; or, where the environment
// names a folder in FLAT2D_SHARED_DRIVE, made there once and read by every later process
// (ctest runs each test in its own process, and the making is most of a replay's time under
// the sanitizers). The folder holds a drive only once it has the file `complete`.
#pragma once

#include <filesystem>
#include <vector>

#include "localization/evaluation/relations.hpp"
#include "localization/localizer/localization_pipeline.hpp"

namespace flat2d::daemon::testing {

struct SimulatedDrive {
  std::filesystem::path dir;
  std::filesystem::path map;      // the prior map file
  std::filesystem::path capture;  // drive 2: lidar.pcap, can.log, vehicle.dbc, truth.tum
  std::filesystem::path can_log;
  std::filesystem::path dbc;
  std::vector<localization::evaluation::TimedPose> truth;
};

const SimulatedDrive& OccludersDrive();

// Makes the drive afresh in FLAT2D_SHARED_DRIVE's folder (what was there is removed, so a
// rebuilt simulator is never judged on an old drive); false when the variable is unset.
bool RemakeSharedDrive();

// The pipeline flat2dd builds, from the shipped configuration files.
std::unique_ptr<localization::LocalizationPipeline> MakeShippedPipeline(const SimulatedDrive& drive);

}  // namespace flat2d::daemon::testing
