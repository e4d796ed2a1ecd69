// Features of real captures: the static VLP-16 sweeps must give the same planes, KITTI's
// HDL-64E clouds must give features without error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "hal/cloud/kitti_bin_file.hpp"
#include "hal/cloud/pcd_file.hpp"
#include "hal/common/angles.hpp"
#include "maps/features3d/feature_extractor.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/range3d/range_frame.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::maps::features3d {
namespace {

FeatureExtractionOptions Shipped() {
  auto options = LoadFeatureOptions(std::filesystem::path(FLAT2D_SOURCE_DIR) / "packaging/config/features3d/features3d.textproto");
  EXPECT_TRUE(options.ok());
  return *options;
}

std::vector<std::filesystem::path> FilesIn(const std::filesystem::path& folder, const std::string& extension) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == extension) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

FeatureSet FeaturesOf(const std::filesystem::path& pcd, bool removal = true) {
  auto cloud = hal::cloud::ReadPcd(pcd);
  EXPECT_TRUE(cloud.ok()) << pcd;
  const range3d::SensorModel sensor = range3d::DetectLidar(cloud->points);
  EXPECT_EQ(sensor, range3d::SensorModel::kVlp16);
  FeatureExtractionOptions options = OptionsForSensor(Shipped(), sensor);
  options.mutable_vertical()->set_enabled(removal);
  FeatureExtractor extractor(ProjectionForSensor(options, sensor), options);
  return extractor.Extract(cloud->points, Eigen::Vector3f::UnitZ());
}

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(p * static_cast<double>(values.size() - 1))];
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.dot(b)))) * kRadToDeg;
}

// How far apart two features of the same thing are: the angle of their normals or
// directions, and the offset (planes: d; lines: the first's point from the second line).
// For planes also where they are seen: the first's centroid from the second plane. Their d
// (distance from the sensor) differs by the normals' angle times the lever from the foot of
// the perpendicular to the points: 1 deg at 2.5 m is 4 cm, though the two planes cross
// among the points.
struct Agreement {
  int looked = 0, found = 0;
  std::vector<double> angle_deg, offset_m, at_centroid_m;
  void Report(const char* what) const {
    std::printf("static VLP-16 %s: %d of %d found again; angle median %.3f p90 %.3f max %.3f deg, offset median %.4f p90 %.4f m",
                what, found, looked, Percentile(angle_deg, 0.5), Percentile(angle_deg, 0.9), Percentile(angle_deg, 1.0),
                Percentile(offset_m, 0.5),
                Percentile(offset_m, 0.9));
    if (!at_centroid_m.empty()) {
      std::printf(", at the centroid median %.4f p90 %.4f max %.4f m", Percentile(at_centroid_m, 0.5),
                  Percentile(at_centroid_m, 0.9), Percentile(at_centroid_m, 1.0));
    }
    std::printf("\n");
  }
};

double Offset(const PlaneFeature& a, const PlaneFeature& b) { return std::abs(a.d - b.d); }
void RecordAtCentroid(const PlaneFeature& a, const PlaneFeature& b, Agreement& out) {
  out.at_centroid_m.push_back(std::abs(b.normal.dot(a.centroid) + b.d));
}
void RecordAtCentroid(const LineFeature&, const LineFeature&, Agreement&) {}
double Offset(const LineFeature& a, const LineFeature& b) {
  const Eigen::Vector3d e = a.point - b.point;
  return (e - e.dot(b.direction) * b.direction).norm();
}
const Eigen::Vector3d& Axis(const PlaneFeature& p) { return p.normal; }
const Eigen::Vector3d& Axis(const LineFeature& l) { return l.direction; }

// Each feature of `first` with at least 30 points, looked for in `other` (angle within 5 deg,
// offset within 0.2 m: the same thing).
template <typename F>
void Compare(const std::vector<F>& first, const std::vector<F>& other, Agreement& out, int min_points = 30) {
  for (const F& p : first) {
    if (p.points < min_points) continue;
    ++out.looked;
    const F* best = nullptr;
    double best_offset = 0.2;
    for (const F& q : other) {
      if (AngleDeg(Axis(p), Axis(q)) > 5.0 || Offset(p, q) >= best_offset) continue;
      best_offset = Offset(p, q);
      best = &q;
    }
    if (best == nullptr) continue;
    ++out.found;
    out.angle_deg.push_back(AngleDeg(Axis(p), Axis(*best)));
    out.offset_m.push_back(best_offset);
    RecordAtCentroid(p, *best, out);
  }
}

// The sensor stood still: the features of the first sweep are looked for in the other four.
// Indoors, with the ground removed, the room gives mostly lines (table legs, shelf posts);
// of its walls behind furniture, one stacks enough rings per column to survive the removal.
TEST(FeatureRealData, StaticVlp16SweepsGiveTheSameFeatures) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/vlp16_nebula_indoor");
  const auto sweeps = FilesIn(folder, ".pcd");
  ASSERT_EQ(sweeps.size(), 5U);
  const FeatureSet first = FeaturesOf(sweeps.front());
  Agreement planes, lines;
  for (std::size_t k = 1; k < sweeps.size(); ++k) {
    const FeatureSet other = FeaturesOf(sweeps[k]);
    Compare(first.planes, other.planes, planes);
    Compare(first.lines, other.lines, lines);
  }
  planes.Report("planes");
  lines.Report("lines");
  ASSERT_GT(lines.looked, 40);
  EXPECT_GE(lines.found, 0.8 * lines.looked);
  EXPECT_LE(Percentile(lines.angle_deg, 0.5), 2.0);  // the line tolerance; short legs tilt most
  EXPECT_LE(Percentile(lines.offset_m, 0.5), 0.02);
  // Planes are few here (docs/benchmarks.md): each found again must agree within the issue's
  // 1 deg and 2 cm where it is seen.
  ASSERT_GE(planes.looked, 4);
  EXPECT_GE(planes.found, planes.looked / 2);
  for (const double angle : planes.angle_deg) EXPECT_LE(angle, 1.0);
  for (const double offset : planes.at_centroid_m) EXPECT_LE(offset, 0.02);
}

// The room's planes (walls, floor, table tops) without the removal, which keeps the walls'
// short columns: the planes of the first sweep found again in the other four within the
// issue's 1 deg and 2 cm.
TEST(FeatureRealData, StaticVlp16SweepsGiveTheSamePlanesWithoutTheRemoval) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/vlp16_nebula_indoor");
  const auto sweeps = FilesIn(folder, ".pcd");
  ASSERT_EQ(sweeps.size(), 5U);
  const FeatureSet first = FeaturesOf(sweeps.front(), false);
  Agreement planes, large;
  for (std::size_t k = 1; k < sweeps.size(); ++k) {
    const FeatureSet other = FeaturesOf(sweeps[k], false);
    Compare(first.planes, other.planes, planes);
    Compare(first.planes, other.planes, large, 50);
  }
  planes.Report("planes without the removal");
  large.Report("planes of 50 points or more without the removal");
  // Measured (docs/benchmarks.md): 12 of 12 found again, angle median 0.33 deg (p90 0.74),
  // at the centroid median ~0.5 cm. Planes must be 0.9 m tall: clutter makes none.
  ASSERT_GE(planes.looked, 12);
  EXPECT_GE(planes.found, planes.looked * 3 / 4);
  EXPECT_LE(Percentile(planes.angle_deg, 0.9), 1.0);
  EXPECT_LE(Percentile(planes.at_centroid_m, 0.9), 0.02);
}

TEST(FeatureRealData, KittiFramesGiveFeatures) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/kitti_odometry_00_frames_000000-000015/velodyne");
  const auto frames = FilesIn(folder, ".bin");
  ASSERT_EQ(frames.size(), 16U);
  FeatureExtractor extractor(range3d::LidarProjection(range3d::SensorModel::kKitti64, 2160), Shipped());
  for (const auto& frame : frames) {
    auto cloud = hal::cloud::ReadKittiBin(frame);
    ASSERT_TRUE(cloud.ok()) << cloud.error().message;
    const FeatureSet& features = extractor.Extract(cloud->points, Eigen::Vector3f::UnitZ());
    EXPECT_GT(features.planes.size() + features.lines.size(), 5U) << frame;
    for (const PlaneFeature& p : features.planes) EXPECT_NEAR(p.normal.norm(), 1.0, 1e-9);
  }
}

}  // namespace
}  // namespace flat2d::maps::features3d
