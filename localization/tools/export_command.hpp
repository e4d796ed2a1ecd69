// `flat2d-map export DRIVE --out DIR --can LOG --dbc DBC --odometry CONFIG [--truth T.tum]`:
// a Velodyne drive's revolutions as PCD files with the sensor's pose at each, so that any
// registration tool (flat2d-map register, PCL, Open3D) can be run on real or simulated
// revolution pairs and judged against the truth (scripts/eval-register's simulated set).
//
// Each complete revolution the CAN odometry covers is deskewed into the sensor frame of its
// first fan (deskewed_drive.hpp) and written as DIR/revolution_NNNNNN.pcd (x y z; N counts
// the revolutions the odometry covers). DIR/sensor_poses.tum holds world_T_sensor at each
// written revolution's first fan: the --truth track's pose there (interpolated, in
// 3D), else the dead-reckoned one.
#pragma once

namespace flat2d::localization::tools {

extern const char* const kExportUsage;

int ExportCommand(int argc, char** argv);

}  // namespace flat2d::localization::tools
