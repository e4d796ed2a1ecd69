// Validation of a loop-closure candidate by registering the two local maps (thesis 6.3.2):
// NICP with KD-tree correspondences on (p, alpha n), alpha = 1/3 (Eq. 6.10), from the
// candidate's guess T*. The maps are unorganized clouds (merged models), hence the KD-tree.
//
// Steps:
//   1. NICP in rounds of shrinking pair distance (eps_d of Eq. 5.6: 2 m, 1 m, 0.5 m), each
//      from the last: T* is a path alignment, up to a lane off (loop_candidates.hpp), more
//      than the 0.5 m of Eq. 5.6 reaches.
//   2. Accepted when the last round succeeds and
//      - its inliers are at least min_inlier_share of the smaller map's points with normals
//        (the maps overlap),
//      - their mean chi2 is at most max_chi2_per_inlier (they lie on each other), and
//      - NICP moved the map no more than max_correction from T* (the basin: a candidate
//        that slides along a corridor to some other fit is not the one proposed).
//   3. Optionally (ambiguity_shift_m above 0), unique: NICP run again from the fit moved by
//      +-ambiguity_shift_m along its least constrained direction (the smallest eigenvector
//      of H's translation block) must not settle on another fit, more than
//      ambiguity_separation_m away, with at least ambiguity_inlier_ratio of the inliers. A
//      road or corridor without features along it fits anywhere along itself, and two
//      such fits agree with each other, so the robust kernel cannot tell them from a true
//      closure.
// The thesis states no limits; these were chosen on the simulated office and campus drives
// (docs/benchmarks.md, "Local-map SLAM").
#pragma once

#include <string>

#include <Eigen/Geometry>

#include "localization/registration/nicp_options.hpp"
#include "localization/registration/registration_result.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::localization::loops {

struct ClosureValidationOptions {
  registration::NicpOptions nicp = DefaultNicp();
  float round_distances_m[3] = {2.0F, 1.0F, 0.5F};  // eps_d of each round
  double min_inlier_share = 0.25;
  double max_chi2_per_inlier = 2.0;
  double max_correction_m = 3.0;
  double max_correction_rad = 0.2;
  double ambiguity_shift_m = 0.0;  // 0: no uniqueness test (step 3)
  double ambiguity_separation_m = 1.0;
  double ambiguity_inlier_ratio = 0.9;

  static registration::NicpOptions DefaultNicp() {
    registration::NicpOptions nicp;
    nicp.kdtree_alpha = 1.0F / 3.0F;  // Eq. 6.10
    nicp.iterations = 10;
    nicp.normal_weight = 9.0;  // normals fitted over R = 0.3 m (nicp_options.hpp: (R / 0.1 m)^2)
    return nicp;
  }
};

struct ClosureValidation {
  bool accepted = false;
  std::string reason;  // why not, when rejected
  registration::RegistrationResult result;  // reference_T_current in result.target_T_source
  double inlier_share = 0.0;
  double chi2_per_inlier = 0.0;
};

// A past map near the reference along the trajectory, for FindAlias: its points and its
// pose in the reference map's frame (from the chain).
struct AliasNeighbour {
  int index = 0;
  const maps::range3d::SurfelCloud* map = nullptr;
  Eigen::Isometry3d reference_T_neighbour = Eigen::Isometry3d::Identity();
};

// Place recognition must be unique among nearby places: a road whose look repeats (trees and
// buildings at a regular spacing) lets the current map fit a past map as well as the one it
// truly overlaps, a whole map or more away, where no shift of one fit reaches (step 3
// cannot see it). The current map is put on the neighbour as the fit put it on the
// reference; if NICP settles there, more than ambiguity_separation_m from the fit, with
// at least ambiguity_inlier_ratio of the fit's inlier share, the place is aliased.
// Returns the reason, or empty when the neighbour offers no other fit.
std::string FindAlias(const maps::range3d::SurfelCloud& current, const ClosureValidation& fit,
                      const AliasNeighbour& neighbour, const ClosureValidationOptions& options);

// `reference` and `current`: the two maps' points with their statistics, each in its own
// map frame; `guess`: reference_T_current from the candidate.
ClosureValidation ValidateClosure(const maps::range3d::SurfelCloud& reference, const maps::range3d::SurfelCloud& current,
                                  const Eigen::Isometry3d& guess, const ClosureValidationOptions& options);

}  // namespace flat2d::localization::loops
