// SNICP, speeded-up NICP (thesis 5.2): the same error and solver as NICP, with
//  - normals by cross products and a block filter instead of eigen-decompositions (5.2.1,
//    maps/range3d/cross_product_normals.hpp);
//  - a pyramid: 3 iterations at 1/4, 1/2 and full resolution (5.3), the coarse levels
//    widening the data association's basin and costing a fraction of the full one;
//  - the new frame moved into the reference's image (Eq. 5.20-5.21), which is how
//    RegisterFrames pairs a source with a fixed target already.
// For depth images (pinhole frames).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "hal/cloud/point_cloud.hpp"
#include "localization/registration/frame_registration.hpp"
#include "localization/registration/nicp_options.hpp"
#include "maps/range3d/cross_product_normals.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::registration {

struct SnicpOptions {
  // Coarse to fine, relative to the frames' image_scale (the working resolution): 160x120,
  // 320x240, 640x480 for a 640x480 camera at image_scale 1; 40x30, 80x60, 160x120 at 4.
  std::vector<int> scales{4, 2, 1};
  int iterations_per_level = 3;      // 5.3
  maps::range3d::CrossProductNormalOptions normals;
};

// A depth frame at every level of the pyramid, coarse to fine; level s is every
// (s x frames.image_scale)-th pixel and row of `depth`.
struct SnicpFrame {
  std::vector<maps::range3d::RangeFrame> levels;
};

SnicpFrame MakeSnicpFrame(const hal::cloud::DepthImage& depth, const maps::range3d::RangeFrameOptions& frames,
                          const SnicpOptions& options);

// Registers source to target level by level; options.iterations is replaced by
// iterations_per_level. result.iterations counts all levels'. A coarse level with too few
// pairs is passed over (the next starts from the same pose); the finest decides.
// Level-by-level registration's rule for a level that paired too few points: a coarse
// level only widens the basin, so the next level starts from `level_guess` again (result
// reset to it, true returned); the finest level's failure stands (false).
bool PassOverSparseLevel(bool finest, const Eigen::Isometry3d& level_guess, RegistrationResult& result);

FrameRegistration RegisterSnicp(const SnicpFrame& target, const SnicpFrame& source, const Eigen::Isometry3d& guess,
                                NicpOptions nicp, const SnicpOptions& options);

}  // namespace flat2d::localization::registration
