// TORO's 2D text format (Grisetti et al., "A tree parameterization for efficiently computing
// maximum likelihood maps using gradient descent", RSS 2007):
//   VERTEX2 id x y theta
//   EDGE2 i j dx dy dtheta inf_xx inf_xy inf_yy inf_tt inf_xt inf_yt
// TORO's information is over the translation error in node i's frame, Ri^T (tj - ti) - tz,
// while g2o's (and this module's, F2) is over Rz^T of it; so reading rotates the
// information into F2's frame, L_g2o = B^T L_toro B with B = diag(Rz, 1), and writing
// rotates back. (Checked on CSAIL and M3500, which ship in both formats: the converted
// TORO information equals the g2o file's to the printed digits.)
#pragma once

#include <istream>
#include <ostream>
#include <string>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

Result<PoseGraph> ReadToro(std::istream& in, const std::string& source);
Result<PoseGraph> ReadToroFile(const std::string& path);

// Nodes and between factors; priors and max-mixture factors are left out.
Status WriteToro(const PoseGraph& graph, std::ostream& out);
Status WriteToroFile(const PoseGraph& graph, const std::string& path);

}  // namespace flat2d::localization::graph
