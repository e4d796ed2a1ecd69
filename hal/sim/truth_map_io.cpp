// Writing a TruthMap as a ROS map_server pair (hal/mapfile/map_server.hpp): truth_map.pgm
// and truth_map.yaml, with a comment saying what its gray values mean.
#include <string>
#include <system_error>

#include "hal/mapfile/map_server.hpp"
#include "hal/sim/truth_map.hpp"

namespace flat2d::hal::sim {

Status WriteTruthMap(const TruthMap& map, const std::filesystem::path& directory_or_stem) {
  if (map.width <= 0 || map.height <= 0 ||
      map.cells.size() != static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height)) {
    return MakeError("truth map: the map is empty or its cells do not match its size");
  }
  std::error_code error;
  const bool is_directory = std::filesystem::is_directory(directory_or_stem, error);
  const std::filesystem::path stem = is_directory ? directory_or_stem / "truth_map" : directory_or_stem;
  const mapfile::GrayMap gray{.width = map.width,
                              .height = map.height,
                              .resolution_m = map.resolution_m,
                              .origin = map.origin,
                              .pixels = map.GrayImage()};
  const std::string legend =
      "flat2d truth map: " + std::to_string(kTruthOccupiedGray) + " = occupied (slammable structure), " +
      std::to_string(kTruthHazardGray) +
      " = hazard (low obstacles, ground steeper than the hazard slope; map_server reads it as unknown), " +
      std::to_string(kTruthFreeGray) + " = free.";
  return mapfile::WriteMapServer(gray, stem, {legend});
}

}  // namespace flat2d::hal::sim
