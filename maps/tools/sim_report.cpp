#include "maps/tools/sim_report.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstdio>
#include <sstream>

#include "hal/sim/simulation_sinks.hpp"
#include "hal/sim/truth_map.hpp"
#include "hal/velodyne/model.hpp"
#include "maps/render/png_writer.hpp"

namespace flat2d::maps::sim_cli {
namespace {

std::string Quote(std::string_view text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned>(c));
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", value);
  return text;
}

std::string DriveToJson(const hal::sim::DriveInfo& drive) {
  return "{\"index\": " + std::to_string(drive.index) + ", \"name\": " + Quote(drive.name) +
         ", \"description\": " + Quote(drive.description) + ", \"duration_s\": " +
         Number(drive.duration_s) + ", \"length_m\": " + Number(drive.length_m) +
         ", \"loop\": " + (drive.loop ? "true" : "false") + "}";
}

double RealTimeFactor(const hal::sim::SimulationSummary& summary) {
  return summary.wall_s > 0.0 ? summary.simulated_s / summary.wall_s : 0.0;
}

}  // namespace

std::string ListToText(const std::vector<WorldListing>& worlds) {
  std::ostringstream text;
  for (const WorldListing& world : worlds) {
    text << world.name << ": " << world.description << "\n";
    for (const hal::sim::DriveInfo& drive : world.drives) {
      char line[160];
      std::snprintf(line, sizeof(line), "  --drive %d  %-14s %7.1f s %8.1f m%s  ", drive.index,
                    drive.name.c_str(), drive.duration_s, drive.length_m, drive.loop ? " loop" : "");
      text << line << drive.description << "\n";
    }
  }
  return text.str();
}

std::string ListToJson(const std::vector<WorldListing>& worlds) {
  std::string json = "{\"worlds\": [";
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    json += (w ? ", " : "") + std::string("{\"name\": ") + Quote(worlds[w].name) +
            ", \"description\": " + Quote(worlds[w].description) + ", \"drives\": [";
    for (std::size_t d = 0; d < worlds[w].drives.size(); ++d) {
      json += (d ? ", " : "") + DriveToJson(worlds[w].drives[d]);
    }
    json += "]}";
  }
  return json + "]}\n";
}

std::string ReportToText(const RunReport& report) {
  const hal::sim::SimulationSummary& s = report.summary;
  std::ostringstream text;
  text << "world:            " << s.world << " (drive " << report.options.drive << ": " << s.drive
       << ", " << Number(s.drive_duration_s) << " s, " << Number(s.drive_length_m) << " m)\n"
       << "sensor:           " << hal::velodyne::ModelName(report.options.lidar.model) << " at "
       << Number(report.options.lidar.rotation_hz) << " Hz, seed " << report.options.seed << "\n"
       << "simulated:        " << Number(s.simulated_s) << " s in " << Number(s.wall_s) << " s ("
       << Number(RealTimeFactor(s)) << "x real time)\n"
       << "data packets:     " << s.data_packets << "\n"
       << "position packets: " << s.position_packets << "\n"
       << "CAN frames:       " << s.can_frames << "\n"
       << "truth poses:      " << s.truth_poses << "\n";
  if (report.out) {
    text << "written to:       " << *report.out << ":";
    for (const std::string& file : report.files) text << " " << file;
    text << "\n";
  }
  if (report.live_sent + report.live_send_errors > 0) {
    text << "sent live:        " << report.live_sent << " (" << report.live_send_errors << " failed)\n";
  }
  return text.str();
}

std::string ReportToJson(const RunReport& report) {
  const hal::sim::SimulationSummary& s = report.summary;
  std::string json = "{\"world\": " + Quote(s.world) + ", \"world_argument\": " +
                     Quote(report.world_argument) + ", \"drive\": " +
                     std::to_string(report.options.drive) + ", \"drive_name\": " + Quote(s.drive) +
                     ", \"drive_duration_s\": " + Number(s.drive_duration_s) +
                     ", \"drive_length_m\": " + Number(s.drive_length_m) +
                     ", \"seed\": " + std::to_string(report.options.seed) +
                     ", \"sensor\": " + Quote(hal::velodyne::ModelName(report.options.lidar.model)) +
                     ", \"rotation_hz\": " + Number(report.options.lidar.rotation_hz) +
                     ", \"data_packets\": " + std::to_string(s.data_packets) +
                     ", \"position_packets\": " + std::to_string(s.position_packets) +
                     ", \"can_frames\": " + std::to_string(s.can_frames) +
                     ", \"truth_poses\": " + std::to_string(s.truth_poses) +
                     ", \"simulated_s\": " + Number(s.simulated_s) +
                     ", \"wall_s\": " + Number(s.wall_s) +
                     ", \"real_time_factor\": " + Number(RealTimeFactor(s));
  if (report.out) {
    json += ", \"out\": " + Quote(*report.out) + ", \"files\": [";
    for (std::size_t i = 0; i < report.files.size(); ++i) {
      json += (i ? ", " : "") + Quote(report.files[i]);
    }
    json += "]";
  }
  json += ", \"live_sent\": " + std::to_string(report.live_sent) +
          ", \"live_send_errors\": " + std::to_string(report.live_send_errors);
  return json + "}\n";
}

std::vector<std::string> OutputFiles(const std::filesystem::path& directory) {
  const std::string stem = hal::sim::kTruthMapStem;
  const std::vector<std::string> candidates = {
      hal::sim::kLidarFile, hal::sim::kCanFile,  hal::sim::kDbcFile, hal::sim::kTruthFile,
      stem + ".pgm",        stem + ".yaml",      stem + ".png"};
  std::vector<std::string> present;
  for (const std::string& name : candidates) {
    if (std::filesystem::is_regular_file(directory / name)) present.push_back(name);
  }
  std::sort(present.begin(), present.end());
  return present;
}

}  // namespace flat2d::maps::sim_cli

namespace flat2d::maps::sim_cli {
namespace {

constexpr Rgb kHazardColour{230, 140, 30};

bool ReadWholeFile(const std::filesystem::path& path, std::string& bytes) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return false;
  char block[65536];
  std::size_t got = 0;
  while ((got = std::fread(block, 1, sizeof(block), file)) > 0) bytes.append(block, got);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  return !failed;
}

// The next header token of a PGM, skipping whitespace and '#' comments.
std::string PgmToken(const std::string& bytes, std::size_t& at) {
  for (;;) {
    while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
    if (at < bytes.size() && bytes[at] == '#') {
      while (at < bytes.size() && bytes[at] != '\n') ++at;
      continue;
    }
    break;
  }
  const std::size_t begin = at;
  while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
  return bytes.substr(begin, at - begin);
}

}  // namespace

Status RenderTruthMapPng(const std::filesystem::path& directory) {
  const std::filesystem::path pgm = directory / (std::string(hal::sim::kTruthMapStem) + ".pgm");
  std::string bytes;
  if (!ReadWholeFile(pgm, bytes)) return MakeError(pgm.string() + ": cannot read");
  std::size_t at = 0;
  const std::string magic = PgmToken(bytes, at);
  const int width = std::atoi(PgmToken(bytes, at).c_str());
  const int height = std::atoi(PgmToken(bytes, at).c_str());
  const int max_value = std::atoi(PgmToken(bytes, at).c_str());
  ++at;  // the single whitespace after the header
  if (magic != "P5" || width <= 0 || height <= 0 || width > kMaxPngSidePx ||
      height > kMaxPngSidePx || max_value != 255 ||
      bytes.size() < at + static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    return MakeError(pgm.string() + ": not an 8-bit binary PGM");
  }
  // Occupied black and free white as map_server shows them; hazard (grey 128 in the PGM)
  // orange, so that curbs and steep ramps stand out from structure.
  RgbImage image(width, height);
  const std::uint8_t* gray = reinterpret_cast<const std::uint8_t*>(bytes.data() + at);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const std::uint8_t value = *gray++;
      image.Set(col, row, value == hal::sim::kTruthHazardGray ? kHazardColour : Rgb{value, value, value});
    }
  }
  return WritePng(image, directory / (std::string(hal::sim::kTruthMapStem) + ".png"));
}

}  // namespace flat2d::maps::sim_cli
