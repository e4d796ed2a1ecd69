// Shared by the simulation run tests: a small world that simulates fast, options for a
// short run, a scratch directory, and reading a file's bytes.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "hal/sim/simulation.hpp"

namespace flat2d::hal::sim::testing {

inline Vec2 Point(double x, double y) {
  Vec2 point;
  point.set_x(x);
  point.set_y(y);
  return point;
}

// A 60 x 40 m yard: flat ground, four walls, two boxes and a pole, and one drive that goes
// 25 m east and turns north (about 9 s at 5 m/s).
inline SceneDescription SmallWorld() {
  SceneDescription world;
  world.set_name("yard");
  Wall* wall = world.add_walls();
  for (const auto& [x, y] : {std::pair{-10.0, -15.0}, {50.0, -15.0}, {50.0, 25.0}, {-10.0, 25.0},
                             {-10.0, -15.0}}) {
    *wall->add_points() = Point(x, y);
  }
  wall->set_thickness_m(0.3);
  wall->set_height_m(3.0);
  Box* box = world.add_boxes();
  *box->mutable_center() = Point(12.0, 6.0);
  box->set_length_m(4.0);
  box->set_width_m(2.0);
  box->set_height_m(1.5);
  Box* shed = world.add_boxes();
  *shed->mutable_center() = Point(20.0, -8.0);
  shed->set_yaw(0.4);
  shed->set_length_m(6.0);
  shed->set_width_m(4.0);
  shed->set_height_m(2.5);
  Cylinder* pole = world.add_cylinders();
  *pole->mutable_center() = Point(5.0, -3.0);
  pole->set_radius_m(0.15);
  pole->set_height_m(4.0);
  Drive* drive = world.add_drives();
  drive->set_name("mapping");
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {25.0, 0.0}, {25.0, 15.0}}) {
    *drive->add_waypoints() = Point(x, y);
  }
  drive->set_speed_mps(5.0);
  drive->set_corner_radius_m(5.0);
  return world;
}

// A short VLP-16 run of the small world (the cheapest model to simulate).
inline SimulationOptions ShortRun(double duration_s = 1.0) {
  SimulationOptions options;
  options.world = SmallWorld();
  options.seed = 7;
  options.duration_s = duration_s;
  options.lidar = DefaultLidarOptions(velodyne::Model::kVlp16);
  return options;
}

// A fresh directory under the temp folder, removed with everything in it at the end.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("flat2d_sim_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// stdio rather than istreambuf_iterator, which GCC 12 -O3 flags with -Wnull-dereference.
inline std::string ReadBytes(const std::filesystem::path& path) {
  std::string bytes;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return bytes;
  char block[65536];
  std::size_t got = 0;
  while ((got = std::fread(block, 1, sizeof(block), file)) > 0) bytes.append(block, got);
  std::fclose(file);
  return bytes;
}

// The lines of `text` without their newlines.
inline std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

}  // namespace flat2d::hal::sim::testing
