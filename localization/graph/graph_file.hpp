// Reading a pose-graph file whatever its format: .graph or .toro is TORO; otherwise the
// first record's tag decides (VERTEX_SE3:QUAT / EDGE_SE3:QUAT: 3D g2o, read by
// g2o_se3_io.hpp; other VERTEX_ / EDGE_ records: 2D g2o; VERTEX2 / EDGE2: TORO), FIX lines
// skipped; a .g2o file whose first record is neither is 2D g2o, so its reader names the
// bad line.
#pragma once

#include <string>
#include <string_view>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

enum class GraphFormat {
  kG2o,     // VERTEX_SE2 / EDGE_SE2
  kG2oSe3,  // VERTEX_SE3:QUAT / EDGE_SE3:QUAT
  kToro,    // VERTEX2 / EDGE2
};
std::string_view GraphFormatName(GraphFormat format);

// An error when the file cannot be opened or its format not recognized.
Result<GraphFormat> DetectGraphFormat(const std::string& path);
// An SE(2) graph; an error for a kG2oSe3 file (read it with ReadG2oSe3File).
Result<PoseGraph> ReadPoseGraphFile(const std::string& path);

}  // namespace flat2d::localization::graph
