// 2D grids as ROS map_server files: an 8-bit PGM image and a YAML file with its resolution
// and origin, the format planners, RViz and map tools already read.
//
// The image's first row is the grid's highest y; `origin` is the world position of the
// lower-left pixel's lower-left corner (map_server's convention, yaw 0 only). The writer
// produces binary P5 PGM and the YAML keys image, resolution, origin, negate, occupied_thresh,
// free_thresh and mode, plus any comment lines the caller gives (what its gray values mean).
// The reader accepts P5 PGM (comments in the header allowed, maxval 255) and resolves the
// image path relative to the YAML file; every failure names the file and what was wrong.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"

namespace flat2d::hal::mapfile {

struct GrayMap {
  int width = 0;
  int height = 0;
  double resolution_m = 0.0;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  std::vector<std::uint8_t> pixels;  // width * height, top row (highest y) first
};

// Writes <stem>.pgm and <stem>.yaml. `comment` lines go at the top of the YAML, each
// prefixed with "# ".
Status WriteMapServer(const GrayMap& map, const std::filesystem::path& stem,
                      const std::vector<std::string>& comment = {});

// Reads a map_server YAML file and the image it names.
Result<GrayMap> ReadMapServer(const std::filesystem::path& yaml_path);

}  // namespace flat2d::hal::mapfile
