// Reading a pose-graph file whatever its format: by extension (.g2o; .graph or .toro for
// TORO), otherwise by the first record's tag (VERTEX_SE2 / EDGE_SE2 / FIX: g2o;
// VERTEX2 / EDGE2: TORO).
#pragma once

#include <string>
#include <string_view>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

enum class GraphFormat { kG2o, kToro };
std::string_view GraphFormatName(GraphFormat format);

// An error when the file cannot be opened or its format not recognized.
Result<GraphFormat> DetectGraphFormat(const std::string& path);
Result<PoseGraph> ReadPoseGraphFile(const std::string& path);

}  // namespace flat2d::localization::graph
