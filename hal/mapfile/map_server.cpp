#include "hal/mapfile/map_server.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include <yaml-cpp/yaml.h>

namespace flat2d::hal::mapfile {
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
  if (!out) return MakeError(path.string() + ": cannot open for writing");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
  out.close();
  if (!out) return MakeError(path.string() + ": cannot write");
  return Status::Ok();
}

// Skips whitespace and '#' comments of a PGM header, then reads one decimal number.
bool ReadHeaderNumber(std::istream& in, long& value) {
  while (true) {
    const int c = in.peek();
    if (c == '#') {
      std::string ignored;
      std::getline(in, ignored);
    } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      in.get();
    } else {
      break;
    }
  }
  return static_cast<bool>(in >> value);
}

Result<GrayMap> ReadPgm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return MakeError(path.string() + ": cannot open");
  std::string magic(2, '\0');
  in.read(magic.data(), 2);
  if (magic != "P5") return MakeError(path.string() + ": not a binary PGM (P5)");
  long width = 0, height = 0, maxval = 0;
  if (!ReadHeaderNumber(in, width) || !ReadHeaderNumber(in, height) || !ReadHeaderNumber(in, maxval)) {
    return MakeError(path.string() + ": truncated PGM header");
  }
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535) {
    return MakeError(path.string() + ": PGM size " + std::to_string(width) + " x " + std::to_string(height) +
                     " out of range");
  }
  if (maxval != 255) return MakeError(path.string() + ": only 8-bit PGM (maxval 255) is supported");
  in.get();  // the single whitespace after maxval
  GrayMap map;
  map.width = static_cast<int>(width);
  map.height = static_cast<int>(height);
  map.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  in.read(reinterpret_cast<char*>(map.pixels.data()), static_cast<std::streamsize>(map.pixels.size()));
  if (in.gcount() != static_cast<std::streamsize>(map.pixels.size())) {
    return MakeError(path.string() + ": PGM data shorter than " + std::to_string(width) + " x " +
                     std::to_string(height));
  }
  return map;
}

}  // namespace

Status WriteMapServer(const GrayMap& map, const std::filesystem::path& stem, const std::vector<std::string>& comment) {
  if (map.width <= 0 || map.height <= 0 ||
      map.pixels.size() != static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height)) {
    return MakeError(stem.string() + ": the map is empty or its pixels do not match its size");
  }
  std::filesystem::path pgm = stem;
  pgm += ".pgm";
  std::filesystem::path yaml = stem;
  yaml += ".yaml";
  const std::string pgm_header = "P5\n" + std::to_string(map.width) + " " + std::to_string(map.height) + "\n255\n";
  if (Status s = WriteFile(pgm, pgm_header, map.pixels); !s) return s;
  std::string text;
  for (const std::string& line : comment) text += "# " + line + "\n";
  text += "image: " + pgm.filename().string() + "\nresolution: " + Number(map.resolution_m) + "\norigin: [" +
          Number(map.origin.x()) + ", " + Number(map.origin.y()) +
          ", 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n";
  return WriteFile(yaml, text, {});
}

Result<GrayMap> ReadMapServer(const std::filesystem::path& yaml_path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path.string());
  } catch (const YAML::Exception& e) {
    return MakeError(yaml_path.string() + ": " + e.what());
  }
  double resolution = 0.0;
  std::string image;
  Eigen::Vector2d origin;
  try {
    if (!root["image"] || !root["resolution"] || !root["origin"]) {
      return MakeError(yaml_path.string() + ": needs image, resolution and origin");
    }
    image = root["image"].as<std::string>();
    resolution = root["resolution"].as<double>();
    const YAML::Node o = root["origin"];
    if (!o.IsSequence() || o.size() != 3) return MakeError(yaml_path.string() + ": origin must be [x, y, yaw]");
    origin = {o[0].as<double>(), o[1].as<double>()};
    if (o[2].as<double>() != 0.0) return MakeError(yaml_path.string() + ": origin yaw other than 0 is not supported");
  } catch (const YAML::Exception& e) {
    return MakeError(yaml_path.string() + ": " + e.what());
  }
  if (!(resolution > 0.0 && std::isfinite(resolution))) {
    return MakeError(yaml_path.string() + ": resolution must be positive");
  }
  if (!origin.allFinite()) return MakeError(yaml_path.string() + ": origin must be finite");
  const std::filesystem::path image_path = std::filesystem::path(image).is_absolute()
                                               ? std::filesystem::path(image)
                                               : yaml_path.parent_path() / image;
  Result<GrayMap> map = ReadPgm(image_path);
  if (!map.ok()) return map;
  map->resolution_m = resolution;
  map->origin = origin;
  return map;
}

}  // namespace flat2d::hal::mapfile
