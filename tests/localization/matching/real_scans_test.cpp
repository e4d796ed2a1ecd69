// Acceptance (b): real laser scans from the GMapping-corrected CARMEN logs of the 2D SLAM
// benchmarks (../shared/data/slam2d/corrected_logs). For pairs of scans 1-5 apart, the map
// is scan A's points at A's corrected pose; scan B is matched from its corrected pose
// perturbed by up to +-0.5 m and +-5 deg, and the result is compared with B's corrected
// pose. The corrected poses are themselves a SLAM estimate: GMapping's relative errors on
// these buildings are a few cm and 0.4-1.3 deg on average (REFERENCE_RESULTS.md, sections
// 3-4), and our matches score higher than the reference poses on most pairs. So two
// figures are checked: (1) agreement with the reference, within 5 cm / 0.5 deg and within
// 10 cm / 1 deg, for stated fractions; (2) convergence, which the reference's errors do not
// blur: the match from the perturbed prediction equals the match from the reference pose
// within one cell and 0.5 deg. Measured (seed 42, 150 pairs each): within 5 cm / 0.5 deg
// 51-61%, within 10 cm / 1 deg 80-89%, converged 79-92%; the floors below sit a few points
// under those figures, so they catch regressions, not the reference's own errors. Only fr079 keeps every scan;
// the other logs keep one scan per 0.5-1 m and 15-20 deg, so their pairs are neighbours.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "hal/carmen/carmen_log.hpp"
#include "localization/matching/correlative_matcher.hpp"
#include "localization/matching/scan_points.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::localization {
namespace {

using hal::carmen::LaserScan;

constexpr double kResolution = 0.05;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMinRange = 0.1;
constexpr double kMaxRange = 30.0;  // beyond: max-range readings (81.9 m, 50 m) and noise
constexpr int kPairs = 150;

Se2 PoseOf(const LaserScan& scan) {
  return Se2(scan.laser_pose.x, scan.laser_pose.y, scan.laser_pose.theta);
}

void ToPoints(const LaserScan& scan, ScanPoints& points) {
  points.Clear();
  points.AddLaserScan(scan.ranges, scan.angle_min, scan.angle_increment, kMinRange, kMaxRange);
}

// The grid holding scan A's points (world frame) with a margin for the search.
MatchGrid MapOf(const LaserScan& scan, const ScanPoints& points) {
  const Se2 world_T_laser = PoseOf(scan);
  Eigen::Vector2d low = world_T_laser.translation();
  Eigen::Vector2d high = low;
  for (const Eigen::Vector2d& p : points.points()) {
    low = low.cwiseMin(world_T_laser * p);
    high = high.cwiseMax(world_T_laser * p);
  }
  GridGeometry geometry;
  geometry.resolution = kResolution;
  geometry.origin = low - Eigen::Vector2d::Constant(2.0);
  geometry.width = static_cast<int>(std::ceil((high.x() - low.x() + 4.0) / kResolution));
  geometry.height = static_cast<int>(std::ceil((high.y() - low.y() + 4.0) / kResolution));
  MatchGrid grid(geometry);
  for (const Eigen::Vector2d& p : points.points()) grid.MarkPoint(world_T_laser * p);
  return grid;
}

struct Tally {
  int pairs = 0;
  int matched = 0;          // status kOk
  int converged = 0;        // same result from the perturbed and the reference prediction
  int within_cell = 0;      // <= 5 cm and <= 0.5 deg
  int within_two = 0;       // <= 10 cm and <= 1 deg
  std::vector<double> translation_errors;
  std::vector<double> rotation_errors;
};

Tally MatchPairs(const std::vector<LaserScan>& scans, std::size_t max_gap, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-0.5, 0.5);
  std::uniform_real_distribution<double> turn(-5.0 * kDeg, 5.0 * kDeg);
  MatcherOptions options;
  options.min_score = 0.3;
  CorrelativeMatcher matcher(MatcherLimits{1000, 2000 * 2000, 12, 512, 6}, options);
  ScanPoints points_a(1000);
  ScanPoints points_b(1000);
  Tally tally;
  const std::size_t stride = std::max<std::size_t>(1, (scans.size() - 6) / kPairs);
  for (std::size_t a = 0; a + 5 < scans.size() && tally.pairs < kPairs; a += stride) {
    const std::size_t b = a + 1 + (a / stride) % max_gap;
    ToPoints(scans[a], points_a);
    ToPoints(scans[b], points_b);
    if (!matcher.SetMap(MapOf(scans[a], points_a)).ok()) continue;
    ++tally.pairs;
    const Se2 truth = PoseOf(scans[b]);
    // Braces: the draws are made in order (a call's arguments have none).
    const Se2 prediction{truth.x() + offset(random), truth.y() + offset(random),
                         truth.theta() + turn(random)};
    const MatchResult result = matcher.Match(points_b.points(), prediction, {0.55, 5.5 * kDeg});
    if (!result.ok()) continue;
    ++tally.matched;
    const MatchResult from_truth = matcher.Match(points_b.points(), truth, {0.55, 5.5 * kDeg});
    if ((from_truth.map_T_vehicle.translation() - result.map_T_vehicle.translation()).norm() <=
            kResolution &&
        std::abs(NormalizeAngle(from_truth.map_T_vehicle.theta() -
                                result.map_T_vehicle.theta())) <= 0.5 * kDeg) {
      ++tally.converged;
    }
    const double dt = (result.map_T_vehicle.translation() - truth.translation()).norm();
    const double dr = std::abs(NormalizeAngle(result.map_T_vehicle.theta() - truth.theta()));
    tally.translation_errors.push_back(dt);
    tally.rotation_errors.push_back(dr);
    if (dt <= kResolution && dr <= 0.5 * kDeg) ++tally.within_cell;
    if (dt <= 2.0 * kResolution && dr <= 1.0 * kDeg) ++tally.within_two;
  }
  return tally;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

struct Required {
  std::size_t max_gap;  // pairs are 1..max_gap scans apart
  double within_cell;   // fractions of the pairs
  double within_two_cells;
  double converged;
};

void CheckLog(const std::filesystem::path& path, const Required& required) {
  Result<hal::carmen::CarmenScans> log = hal::carmen::ReadCarmenLaserScans(path);
  ASSERT_TRUE(log.ok()) << log.error().message;
  ASSERT_GT(log->scans.size(), 300u);
  const Tally tally = MatchPairs(log->scans, required.max_gap, 42);
  const double fraction = static_cast<double>(tally.within_cell) / tally.pairs;
  const double fraction_two = static_cast<double>(tally.within_two) / tally.pairs;
  const double converged = static_cast<double>(tally.converged) / tally.pairs;
  std::printf("%s: %d pairs 1-%zu apart, %d matched, %d converged; against the reference %d "
              "(%.1f%%) within 5 cm and 0.5 deg, %d (%.1f%%) within 10 cm and 1 deg; median "
              "error %.4f m, %.3f deg\n",
              path.filename().c_str(), tally.pairs, required.max_gap, tally.matched,
              tally.converged, tally.within_cell, 100.0 * fraction, tally.within_two,
              100.0 * fraction_two, Median(tally.translation_errors),
              Median(tally.rotation_errors) / kDeg);
  EXPECT_GE(tally.pairs, 100);
  EXPECT_GE(converged, required.converged);
  EXPECT_GE(fraction, required.within_cell);
  EXPECT_GE(fraction_two, required.within_two_cells);
}

TEST(RealScansTest, IntelResearchLab) {
  FLAT2D_REQUIRE_DATA(path, "slam2d/corrected_logs/intel-corrected.log.gz");
  CheckLog(path, Required{1, 0.45, 0.80, 0.80});  // measured 51%, 85%, 86%
}

TEST(RealScansTest, FreiburgBuilding079) {
  FLAT2D_REQUIRE_DATA(path, "slam2d/corrected_logs/freiburg-079-corrected.log.gz");
  CheckLog(path, Required{5, 0.45, 0.75, 0.85});  // measured 51%, 80%, 92%
}

TEST(RealScansTest, Aces) {
  FLAT2D_REQUIRE_DATA(path, "slam2d/corrected_logs/aces-corrected.log.gz");
  CheckLog(path, Required{1, 0.55, 0.85, 0.75});  // measured 60%, 89%, 79%
}

TEST(RealScansTest, MitCsail) {
  FLAT2D_REQUIRE_DATA(path, "slam2d/corrected_logs/csail-corrected.log.gz");
  CheckLog(path, Required{1, 0.55, 0.85, 0.85});  // measured 61%, 88%, 91%
}

}  // namespace
}  // namespace flat2d::localization
