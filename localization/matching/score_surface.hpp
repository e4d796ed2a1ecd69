// What the score surface around the best candidate says beyond its argmax: a sub-cell
// pose and a covariance (Olson 2009, section III-C).
//
// Refinement: with bilinear table lookups the score is a continuous function of the pose;
// Levenberg-Marquardt on sum (1 - T(p_i))^2 from the best grid candidate (Gauss-Newton with
// the bilinear gradient, as Hess et al. 2016 refine with a bicubic grid) moves the pose
// below the grid's cell and heading steps, within one step of the grid pose.
//
// Covariance: the candidates within +-radius cells and +-radius headings of the peak are
// weighted by a likelihood exp(k (s_i - s_best)), s the fraction of points on structure and
// k the number of points treated as independent (min(points, effective_points): neighbouring
// points are not), and the covariance is their weighted second moment about the weighted
// mean, plus the variance of the grid's own quantization (step^2 / 12). Along a direction
// the scene does not constrain, every candidate scores alike and the variance grows to that
// of the sampled span; across a wall it collapses to the quantization floor.
#pragma once

#include <span>

#include <Eigen/Core>

#include "localization/matching/branch_and_bound.hpp"
#include "localization/matching/score_table.hpp"
#include "localization/odometry/se2.hpp"

namespace flat2d::localization {

struct SurfaceOptions {
  int radius_cells = 6;            // covariance samples: +-cells in x and y...
  int stride_cells = 2;            // ...every stride_cells cells (fewer lookups, same span)
  int radius_headings = 2;         // and +-heading steps
  double effective_points = 100.0;  // cap on the points counted as independent evidence
};

// Fraction (0..1) of `points` (vehicle frame) on structure at map_T_vehicle, bilinearly.
double ContinuousScore(const ScoreTable& table, std::span<const Eigen::Vector2d> points,
                       const Se2& map_T_vehicle);

// Levenberg-Marquardt on the bilinear surface from `start`: minimizes sum (1 - T(p_i))^2
// over (x, y, theta), at most `iterations` steps, each kept only if the cost drops; the
// result stays within `max_shift` metres and `max_turn` radians of `start`.
Se2 RefineContinuous(const ScoreTable& table, std::span<const Eigen::Vector2d> points,
                     const Se2& start, int iterations, double max_shift, double max_turn);

// Covariance of (x, y, theta) from the discretized surface around `best`.
Eigen::Matrix3d SurfaceCovariance(const SearchProblem& problem, const Candidate& best,
                                  double resolution, double angular_step,
                                  const SurfaceOptions& options);

}  // namespace flat2d::localization
