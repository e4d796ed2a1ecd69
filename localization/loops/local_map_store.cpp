#include "localization/loops/local_map_store.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <unordered_set>
#include <utility>

#include "hal/cloud/ply_file.hpp"
#include "hal/cloud/ply_writer.hpp"
#include "maps/range3d/neighbour_statistics.hpp"

namespace flat2d::localization::loops {
namespace {

// A voxel's key: 21 bits per axis, +-104 km at 0.1 m.
std::uint64_t VoxelKey(const Eigen::Vector3f& p, float inverse_size) {
  auto axis = [&](float v) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v * inverse_size)) + (1 << 20)) & 0x1FFFFF;
  };
  return axis(p.x()) | (axis(p.y()) << 21) | (axis(p.z()) << 42);
}

}  // namespace

LocalMapStore::LocalMapStore(std::filesystem::path directory, const LocalMapStoreOptions& options)
    : directory_(std::move(directory)), options_(options) {}

Status LocalMapStore::Create() const {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error) return MakeError(directory_.string() + ": cannot create (" + error.message() + ")");
  return Status::Ok();
}

std::filesystem::path LocalMapStore::PointsPath(int index) const {
  char name[32];
  std::snprintf(name, sizeof name, "map_%04d.ply", index);
  return directory_ / name;
}

std::filesystem::path LocalMapStore::TrajectoryPath(int index) const {
  return std::filesystem::path(PointsPath(index)).replace_extension(".tum");
}

Status LocalMapStore::WritePoints(int index, const maps::range3d::SurfelCloud& points,
                                  const Eigen::Isometry3d& world_T_map) const {
  const Eigen::Isometry3f map_T_world = world_T_map.inverse().cast<float>();
  const auto inverse_size = static_cast<float>(1.0 / options_.voxel_m);
  std::unordered_set<std::uint64_t> occupied;
  std::vector<Eigen::Vector3f> kept_points, kept_normals;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points.has_normal(i)) continue;
    const Eigen::Vector3f p = map_T_world * points.points[i];
    if (!occupied.insert(VoxelKey(p, inverse_size)).second) continue;
    kept_points.push_back(p);
    kept_normals.push_back(map_T_world.linear() * points.normals[i]);
  }
  return hal::cloud::WritePly(PointsPath(index), kept_points, kept_normals);
}

Status LocalMapStore::WriteTrajectory(int index, const std::vector<hal::trajectory::StampedPose>& map_T_vehicle) const {
  return hal::trajectory::WriteTum(map_T_vehicle, TrajectoryPath(index));
}

Result<hal::cloud::PointCloud> LocalMapStore::ReadStored(int index) const {
  auto read = hal::cloud::ReadPly(PointsPath(index));
  if (!read.ok()) return read.error();
  if (read->normals.size() != read->points.size()) return MakeError(PointsPath(index).string() + ": no normals");
  return read;
}

Result<maps::range3d::SurfelCloud> LocalMapStore::ReadPoints(int index) const {
  auto read = ReadStored(index);
  if (!read.ok()) return read.error();
  maps::range3d::SurfelCloud cloud;
  cloud.Resize(read->points.size());
  cloud.points = std::move(read->points);
  maps::range3d::ComputeNeighbourStatistics(options_.statistics, Eigen::Vector3f::Zero(), cloud);
  // The side each point was seen from, as the model knew it (the map's origin is only one
  // of the viewpoints).
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.has_normal(i) && cloud.normals[i].dot(read->normals[i]) < 0.0F) cloud.normals[i] = -cloud.normals[i];
  }
  return cloud;
}

}  // namespace flat2d::localization::loops
