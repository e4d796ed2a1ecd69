// What flat2d-sim prints and renders besides the simulator's own files: the world list,
// the run's summary (text or one JSON object), and truth_map.png drawn from the
// truth_map.pgm the file sink wrote (the hal library may not depend on maps/render, so the
// picture is made here, from the file a user also gets).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/sim/simulation.hpp"

namespace flat2d::maps::sim_cli {

struct WorldListing {
  std::string name;
  std::string description;
  std::vector<hal::sim::DriveInfo> drives;
};

std::string ListToText(const std::vector<WorldListing>& worlds);
std::string ListToJson(const std::vector<WorldListing>& worlds);

struct RunReport {
  std::string world_argument;
  const hal::sim::SimulationOptions& options;
  const hal::sim::SimulationSummary& summary;
  std::optional<std::string> out;
  std::vector<std::string> files;  // written into out
  std::uint64_t live_sent = 0;
  std::uint64_t live_send_errors = 0;
};

std::string ReportToText(const RunReport& report);
std::string ReportToJson(const RunReport& report);

// The names of the simulator's output files present in `directory`, sorted.
std::vector<std::string> OutputFiles(const std::filesystem::path& directory);

// Renders DIR/truth_map.pgm (binary P5, map_server values) to DIR/truth_map.png.
Status RenderTruthMapPng(const std::filesystem::path& directory);

}  // namespace flat2d::maps::sim_cli
