#include "hal/trajectory/kitti_pose_file.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include "hal/trajectory/transform_file.hpp"

namespace flat2d::hal::trajectory {

Result<std::vector<Eigen::Isometry3d>> ParseKittiPoses(std::string_view text, std::string_view source_name) {
  std::vector<Eigen::Isometry3d> poses;
  std::istringstream lines{std::string(text)};
  std::string line;
  for (int line_number = 1; std::getline(lines, line); ++line_number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = std::string(source_name) + ": line " + std::to_string(line_number);
    auto pose = ParseTransform(line, where);
    if (!pose.ok()) return pose.error();
    poses.push_back(*pose);
  }
  if (poses.empty()) return MakeError(std::string(source_name) + ": no poses");
  return poses;
}

namespace {

// The file's text through `parse(text, source_name)`, the file named in its errors.
template <typename Parse>
auto ReadAndParse(const std::filesystem::path& path, Parse parse) -> decltype(parse(std::string_view(), std::string_view())) {
  std::ifstream file(path);
  if (!file) return MakeError(path.string() + ": cannot open");
  std::stringstream text;
  text << file.rdbuf();
  return parse(text.str(), path.string());
}

}  // namespace

Result<std::vector<Eigen::Isometry3d>> ReadKittiPoses(const std::filesystem::path& path) {
  return ReadAndParse(path, ParseKittiPoses);
}

Eigen::Isometry3d VehicleFromKittiCamera(const Eigen::Isometry3d& world_T_cam0) {
  // cam0_T_vehicle: the vehicle's x (forward) is the camera's z, y (left) is -x, z (up) is -y.
  Eigen::Matrix3d cam_R_vehicle;
  cam_R_vehicle << 0, -1, 0,  //
      0, 0, -1,               //
      1, 0, 0;
  Eigen::Isometry3d cam_T_vehicle = Eigen::Isometry3d::Identity();
  cam_T_vehicle.linear() = cam_R_vehicle;
  // The same change of axes on the world side keeps the world's first pose the identity.
  return cam_T_vehicle.inverse() * world_T_cam0 * cam_T_vehicle;
}

Result<Eigen::Isometry3d> ParseKittiCalibration(std::string_view text, std::string_view source_name) {
  std::istringstream lines{std::string(text)};
  std::string line;
  for (int line_number = 1; std::getline(lines, line); ++line_number) {
    if (!line.starts_with("Tr:")) continue;
    return ParseTransform(std::string_view(line).substr(3), std::string(source_name) + ": line " + std::to_string(line_number));
  }
  return MakeError(std::string(source_name) + ": no Tr: line (cam0_T_velo)");
}

Result<Eigen::Isometry3d> ReadKittiCalibration(const std::filesystem::path& path) {
  return ReadAndParse(path, ParseKittiCalibration);
}

std::vector<Eigen::Isometry3d> VelodyneFromKittiCamera(const std::vector<Eigen::Isometry3d>& world_T_cam0,
                                                       const Eigen::Isometry3d& cam0_T_velo) {
  std::vector<Eigen::Isometry3d> world_T_velo;
  if (world_T_cam0.empty()) return world_T_velo;
  const Eigen::Isometry3d first_velo_T_world = cam0_T_velo.inverse() * world_T_cam0.front().inverse();
  for (const Eigen::Isometry3d& pose : world_T_cam0) world_T_velo.push_back(first_velo_T_world * pose * cam0_T_velo);
  return world_T_velo;
}

}  // namespace flat2d::hal::trajectory
