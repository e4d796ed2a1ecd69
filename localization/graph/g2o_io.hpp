// g2o's 2D text format (Kuemmerle et al., "g2o: A general framework for graph optimization",
// ICRA 2011), the format the public pose-graph benchmarks ship in:
//   VERTEX_SE2 id x y theta
//   EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33   (upper triangle of the information)
//   FIX id [id ...]
// '#' starts a comment. The 3D types (VERTEX_SE3:QUAT, EDGE_SE3:QUAT) are refused here:
// g2o_se3_io.hpp reads 3D files. Every error names the source and the line.
#pragma once

#include <istream>
#include <ostream>
#include <string>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

// `source` names the stream in errors (usually the file path).
Result<PoseGraph> ReadG2o(std::istream& in, const std::string& source);
Result<PoseGraph> ReadG2oFile(const std::string& path);

// Writes every node's estimate, FIX lines for fixed nodes and the between factors. Priors and
// max-mixture factors have no EDGE_SE2 form and are left out.
Status WriteG2o(const PoseGraph& graph, std::ostream& out);
Status WriteG2oFile(const PoseGraph& graph, const std::string& path);

}  // namespace flat2d::localization::graph
