// Closure edits (the refiner of thesis 6.3.4): a text file that adds or removes loop
// closures between local maps before the graph is solved. One edit per line, `#` starts a
// comment:
//
//   add REFERENCE CURRENT x y z qx qy qz qw   a closure reference_T_current (metres, unit
//                                             quaternion), taken as validated
//   remove REFERENCE CURRENT                  every closure found between the two maps
//
// REFERENCE and CURRENT are local-map indices (map_NNNN in DIR/local_maps; graph.g2o's
// vertex ids).
#pragma once

#include <filesystem>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"

namespace flat2d::localization::loops {

struct ClosureEdits {
  struct Addition {
    int reference = 0;
    int current = 0;
    Eigen::Isometry3d reference_T_current = Eigen::Isometry3d::Identity();
  };
  std::vector<Addition> additions;
  std::vector<std::pair<int, int>> removals;  // (reference, current)
};

// Errors name the source and line: an unknown verb, a missing or extra field, a number that
// does not parse, a negative index, a quaternion that is not unit length (within 1e-3).
Result<ClosureEdits> ParseClosureEdits(std::string_view text, std::string_view source_name);
Result<ClosureEdits> ReadClosureEdits(const std::filesystem::path& path);

}  // namespace flat2d::localization::loops
