// flat2dd's configuration file (flat2dd_config.proto) and everything it names, loaded and
// checked before the daemon opens a socket: a bad file stops start-up with the file, the
// field and what is wrong, and a SIGHUP reload that fails leaves the running daemon as it was.
//
// Steps: (1) parse the text proto (unknown fields: file:line:column); (2) fill the fields
// left at zero with their documented defaults; (3) resolve relative paths against the
// configuration file's folder; (4) check values and combinations; (5) load the files it
// names (DBC, odometry, grid and localizer options, the map's header).
#pragma once

#include <filesystem>
#include <memory>

#include "daemon/config/flat2dd_config.pb.h"
#include "hal/can/dbc.hpp"
#include "hal/common/error.hpp"
#include "localization/localizer/localizer.hpp"
#include "localization/odometry/odometry_config.pb.h"
#include "maps/grid/structure_grid_options.pb.h"
#include "maps/prior_map/prior_map_reader.hpp"

namespace flat2d::daemon {

// Steps 1-4: the configuration with defaults filled in and paths absolute.
Result<DaemonConfig> LoadDaemonConfig(const std::filesystem::path& path);

// Step 4 alone, for a message built in code; errors are prefixed with `source_name`.
Status ValidateDaemonConfig(const DaemonConfig& config, std::string_view source_name);

// Step 5: what the localization pipeline is built from.
struct DaemonInputs {
  DaemonConfig config;
  hal::can::Dbc dbc;
  localization::OdometryConfig odometry;
  maps::StructureGridOptions grid;
  localization::LocalizerOptions localizer;
  std::unique_ptr<maps::PriorMapReader> map;
};

Result<DaemonInputs> LoadDaemonInputs(const std::filesystem::path& config_path);

}  // namespace flat2d::daemon
