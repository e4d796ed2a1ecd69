// g2o's 3D pose-graph records (Kuemmerle et al., "g2o: A general framework for graph
// optimization", ICRA 2011), the format of the public SE(3) benchmarks (sphere, torus,
// garage, cubicle):
//   VERTEX_SE3:QUAT id x y z qx qy qz qw
//   EDGE_SE3:QUAT i j x y z qx qy qz qw I11 I12 .. I16 I22 .. I66  (upper triangle of the
//                                          6x6 information, row by row, translation first)
//   FIX id [id ...]
// '#' starts a comment. Steps: split each line into fields, parse and check them (every
// error is "<source>:<line>: <what>"), then map vertex ids to node indices sorted by id.
// Checks beyond the numbers: a quaternion must have unit norm within 1e-3 (it is then
// normalized; files print 6-7 digits) and an information matrix must give positive SE-Sync
// weights (se3_costs.hpp: both diagonal blocks with a positive finite trace of the
// inverse); it need not be definite (the published cubicle graph's are often not). When the file has vertex lines, every edge must
// name vertices among them; a file of edges only yields nodes without estimates. 2D records
// in a 3D file are refused: the two cannot be mixed.
#pragma once

#include <istream>
#include <ostream>
#include <string>

#include "hal/common/error.hpp"
#include "localization/graph/se3_pose_graph.hpp"

namespace flat2d::localization::graph {

// `source` names the stream in errors (usually the file path).
Result<Se3PoseGraph> ReadG2oSe3(std::istream& in, const std::string& source);
Result<Se3PoseGraph> ReadG2oSe3File(const std::string& path);

// Writes every node's estimate, FIX lines for fixed nodes and the between factors with
// their information, numbers with enough digits to read back exactly.
Status WriteG2oSe3(const Se3PoseGraph& graph, std::ostream& out);
Status WriteG2oSe3File(const Se3PoseGraph& graph, const std::string& path);

}  // namespace flat2d::localization::graph
