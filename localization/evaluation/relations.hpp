// The relations metric of the 2D SLAM benchmarks (Kuemmerle et al., "On measuring the
// accuracy of SLAM algorithms", Autonomous Robots 27, 2009): a trajectory is judged by the
// relative poses it gives between pairs of times, against reference relations.
//
// A relation (t1, t2, d*) says where the robot was at t2 in its frame at t1. For each, the
// estimate's d = x(t1)^-1 x(t2) is formed and the error e = d*^-1 d; reported are the mean
// and standard deviation over all relations of |e_t| (m) and |e_theta| (deg), and of their
// squares (m^2, deg^2), the four rows the published tables use.
//
// Relations come from a Freiburg .relations file ("t1 t2 x y z roll pitch yaw", z, roll and
// pitch 0) or are drawn from a reference trajectory (MakeRelations): every pose with the
// next one at least `min_step_m` further along the path (local accuracy), and every pair
// that the reference puts within `loop_radius_m` of each other after at least
// `loop_min_path_m` of travel in between (global consistency at revisits), at most one such
// pair per pose. The estimate's pose at a relation's time is interpolated between its two
// neighbouring poses, when they are at most `max_gap_s` apart; relations that fall outside
// the estimate are counted, not scored.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization::evaluation {

struct TimedPose {
  double time_s = 0.0;
  Se2 pose;
};

struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Se2 delta;  // pose at t2 in the frame of the pose at t1
};

Result<std::vector<Relation>> ReadRelations(const std::filesystem::path& path);
Result<std::vector<Relation>> ParseRelations(std::string_view text, std::string_view source_name);
Status WriteRelations(const std::vector<Relation>& relations, const std::filesystem::path& path);

struct RelationSampling {
  double min_step_m = 0.5;
  double loop_radius_m = 2.0;
  double loop_min_path_m = 10.0;
};
std::vector<Relation> MakeRelations(const std::vector<TimedPose>& reference, const RelationSampling& sampling = {});

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

struct RelationsError {
  std::size_t relations = 0;  // scored
  std::size_t unmatched = 0;  // a time the estimate does not cover
  MeanStd translation_m;
  MeanStd translation_sq_m2;
  MeanStd rotation_deg;
  MeanStd rotation_sq_deg2;
};

// `estimate` in increasing time order.
RelationsError EvaluateRelations(const std::vector<TimedPose>& estimate, const std::vector<Relation>& relations,
                                 double max_gap_s = 1.0);

// The pose at `time_s`, interpolated; false when no two poses at most max_gap_s apart
// bracket it (a time within 2 us of a pose is that pose, and needs no neighbour).
bool PoseAt(const std::vector<TimedPose>& trajectory, double time_s, double max_gap_s, Se2& pose);

}  // namespace flat2d::localization::evaluation
