// The pictures `flat2d-eval traj --plot` writes (issue 9 item 6): the heading error's
// histogram in kHeadingBinRad bins (as thesis Fig. 7.10), and the trajectories over the map.
//
// Histogram: one bar per bin, its height the share of poses in it (full height = 100 %),
// the 0.02 and 0.025 rad bin edges marked in red and orange, the last bar (everything
// beyond 0.1 rad) in grey. Trajectories: the map's classes in the thesis' colours (or a
// white canvas without a map) under the truth (green), the estimate (blue) and the
// open-loop odometry (red), all in the truth's frame, scaled so the longer side is at most
// max_side_px pixels.
#pragma once

#include <vector>

#include "localization/evaluation/relations.hpp"
#include "localization/evaluation/trajectory_error.hpp"
#include "maps/grid/class_grid.hpp"
#include "maps/render/image.hpp"

namespace flat2d::localization {

maps::RgbImage PlotHeadingHistogram(const evaluation::TrajectoryError& error);

struct TrajectoryPlot {
  const std::vector<evaluation::TimedPose>* truth = nullptr;
  const std::vector<evaluation::TimedPose>* estimate = nullptr;
  const std::vector<evaluation::TimedPose>* odometry = nullptr;  // optional
  const maps::ClassGrid* map = nullptr;                          // optional
  double margin_m = 10.0;
  int max_side_px = 2000;
};

maps::RgbImage PlotTrajectories(const TrajectoryPlot& plot);

}  // namespace flat2d::localization
