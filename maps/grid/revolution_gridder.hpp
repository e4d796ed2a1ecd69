// Structure grids from a stream of fans, one per revolution, built as the packets arrive
// (DESIGN.md: "per packet, incremental"; issue 6 item 5).
//
// Steps: (1) each fan is checked against the azimuth cut (hal/velodyne/azimuth_cut.hpp); (2)
// the first fan of a revolution fixes the grid frame, local_T_grid = the vehicle's pose then,
// so the grid is centred on the vehicle; (3) every fan is placed with grid_T_vehicle(t_fan) =
// local_T_grid^-1 local_T_vehicle(t_fan) from the pose source (motion compensation; without a
// pose for t the reference pose is used and the fan is counted); (4) at the cut the grid is
// finished and published, and building goes on in the other of two buffers, so the published
// grid stays valid until the next revolution completes. Everything is sized in Create.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "hal/velodyne/azimuth_cut.hpp"
#include "hal/velodyne/fan.hpp"
#include "maps/grid/structure_grid_builder.hpp"
#include "maps/grid/vehicle_pose_source.hpp"

namespace flat2d::maps {

struct PublishedGrid {
  const ClassGrid* grid = nullptr;
  Eigen::Isometry2d local_T_grid = Eigen::Isometry2d::Identity();  // the reference pose
  TimeNs start_ns = 0;   // first fan
  TimeNs end_ns = 0;     // last fan
  std::uint64_t sequence = 0;
  bool complete = false;  // both ends are cuts (not the stream's first or last partial turn)
  int fans = 0;
  int fans_without_pose = 0;  // placed at the reference pose: no odometry for their time
};

class RevolutionGridder {
 public:
  // poses may be null: the sensor is then taken as standing still.
  static Result<RevolutionGridder> Create(const hal::velodyne::LaserTable& table,
                                          const StructureGridOptions& options, const VehiclePoseSource* poses,
                                          double cut_azimuth_rad = 0.0);

  // Adds fans in time order (one packet's); returns the grid this call completed, or null.
  const PublishedGrid* Add(std::span<const hal::velodyne::Fan> fans);
  // Ends the stream: publishes the partial revolution collected so far (null if none).
  const PublishedGrid* Flush();

 private:
  RevolutionGridder(StructureGridBuilder first, StructureGridBuilder second, const VehiclePoseSource* poses,
                    double cut_azimuth_rad);
  void StartRevolution(const hal::velodyne::Fan& fan);
  void AddFan(const hal::velodyne::Fan& fan);
  const PublishedGrid* Publish(bool complete);

  std::array<StructureGridBuilder, 2> builders_;
  std::array<PublishedGrid, 2> grids_;
  int filling_ = 0;
  bool started_ = false;          // a revolution is being built
  bool started_at_cut_ = false;   // ... and it began at a cut
  const VehiclePoseSource* poses_;
  hal::velodyne::AzimuthCut cut_;
  Eigen::Isometry2d grid_T_local_ = Eigen::Isometry2d::Identity();
  std::uint64_t next_sequence_ = 0;
};

}  // namespace flat2d::maps
