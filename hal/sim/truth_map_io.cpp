// Writing a TruthMap as a ROS map_server pair: truth_map.pgm and truth_map.yaml.
#include <charconv>
#include <fstream>
#include <string>
#include <system_error>

#include "hal/sim/truth_map.hpp"

namespace flat2d::hal::sim {
namespace {

// Shortest text that reads back as the same double.
std::string Number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

Status WriteFile(const std::filesystem::path& path, const std::string& header,
                 const std::vector<std::uint8_t>& body) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return MakeError("truth map: cannot open " + path.string() + " for writing");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
  out.close();
  if (!out) return MakeError("truth map: cannot write " + path.string());
  return Status::Ok();
}

std::string YamlText(const TruthMap& map, const std::string& image_name) {
  return "# flat2d truth map: " + std::to_string(kTruthOccupiedGray) +
         " = occupied (slammable structure), " + std::to_string(kTruthHazardGray) +
         " = hazard (low obstacles, ground steeper than the hazard slope; map_server reads it "
         "as unknown), " +
         std::to_string(kTruthFreeGray) + " = free.\n" + "image: " + image_name + "\n" +
         "resolution: " + Number(map.resolution_m) + "\n" + "origin: [" +
         Number(map.origin.x()) + ", " + Number(map.origin.y()) + ", 0.0]\n" + "negate: 0\n" +
         "occupied_thresh: 0.65\n" + "free_thresh: 0.196\n" + "mode: trinary\n";
}

}  // namespace

Status WriteTruthMap(const TruthMap& map, const std::filesystem::path& directory_or_stem) {
  if (map.width <= 0 || map.height <= 0 ||
      map.cells.size() != static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height)) {
    return MakeError("truth map: the map is empty or its cells do not match its size");
  }
  std::error_code error;
  const bool is_directory = std::filesystem::is_directory(directory_or_stem, error);
  const std::filesystem::path stem =
      is_directory ? directory_or_stem / "truth_map" : directory_or_stem;
  std::filesystem::path pgm = stem;
  pgm += ".pgm";
  std::filesystem::path yaml = stem;
  yaml += ".yaml";
  const std::string pgm_header =
      "P5\n" + std::to_string(map.width) + " " + std::to_string(map.height) + "\n255\n";
  if (Status s = WriteFile(pgm, pgm_header, map.GrayImage()); !s) return s;
  return WriteFile(yaml, YamlText(map, pgm.filename().string()), {});
}

}  // namespace flat2d::hal::sim
