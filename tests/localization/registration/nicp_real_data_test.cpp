// NICP on the real 3D data of ../shared/data (issue 11's acceptance tolerances): the
// HDL-32E pair against both published references, static VLP-16 sweeps against identity,
// KITTI 00 against its GPS/INS truth, Stanford bunny scans against bun.conf, TUM fr1/rpy
// depth pairs against the motion-capture truth.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/testing/pose_error.hpp"

#include "hal/cloud/tum_depth_png.hpp"
#include "hal/trajectory/transform_file.hpp"
#include "hal/trajectory/tum_file.hpp"
#include "localization/registration/frame_registration.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::localization::registration {
namespace {

using maps::range3d::RangeFrame;
using maps::range3d::RangeFrameOptions;

RangeFrame LoadOrDie(const std::filesystem::path& path, const RangeFrameOptions& options = {}) {
  auto frame = maps::range3d::LoadRangeFrame(path, options);
  EXPECT_TRUE(frame.ok()) << frame.error().message;
  return frame.ok() ? std::move(*frame) : RangeFrame{};
}

Eigen::Isometry3d TransformOrDie(const std::filesystem::path& path) {
  auto transform = hal::trajectory::ReadTransformFile(path);
  EXPECT_TRUE(transform.ok()) << transform.error().message;
  return transform.ok() ? *transform : Eigen::Isometry3d::Identity();
}

TEST(NicpRealData, Hdl32ePairFromIdentityLandsOnBothReferences) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/hdl32e_fast_gicp_pair");
  const RangeFrame target = LoadOrDie(folder / "251370668.pcd");
  const RangeFrame source = LoadOrDie(folder / "251371071.pcd");
  ASSERT_EQ(target.sensor, maps::range3d::SensorModel::kHdl32e);
  const FrameRegistration r =
      RegisterFrames(target, source, Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp, NicpOptions{});
  ASSERT_TRUE(r.result.ok());
  // The two references disagree by 1.9 cm / 0.23 deg (PROVENANCE.md): 3 cm / 0.3 deg of each.
  for (const char* reference : {"relative_fast_gicp.txt", "T_target_source_small_gicp.txt"}) {
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, TransformOrDie(folder / reference));
    std::printf("%s: %.4f m %.3f deg\n", reference, e.translation_m, e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.03) << reference;
    EXPECT_LT(e.rotation_deg, 0.3) << reference;
  }
}

std::vector<std::filesystem::path> SweepsIn(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> sweeps;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".pcd") sweeps.push_back(entry.path());
  }
  std::sort(sweeps.begin(), sweeps.end());
  return sweeps;
}

TEST(NicpRealData, StaticVlp16SweepsRegisterToIdentity) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/vlp16_nebula_indoor");
  const std::vector<std::filesystem::path> sweeps = SweepsIn(folder);
  ASSERT_EQ(sweeps.size(), 5U);
  for (std::size_t k = 0; k + 1 < sweeps.size(); ++k) {
    const RangeFrame target = LoadOrDie(sweeps[k]);
    const RangeFrame source = LoadOrDie(sweeps[k + 1]);
    ASSERT_EQ(source.sensor, maps::range3d::SensorModel::kVlp16);
    const FrameRegistration r =
        RegisterFrames(target, source, Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp, NicpOptions{});
    ASSERT_TRUE(r.result.ok());
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, Eigen::Isometry3d::Identity());
    std::printf("sweeps %zu-%zu: %.4f m %.3f deg\n", k, k + 1, e.translation_m, e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.01);
    EXPECT_LT(e.rotation_deg, 0.1);
  }
}

// A pair registered from identity over the frames' own radius, then over `radii` (both
// frames refitted, so registered last): each result's error against `truth`.
struct RadiusComparison {
  testing::PoseError one_radius, coarse_to_fine;
  int coarse_to_fine_iterations = 0;
};

RadiusComparison CompareRadii(const RangeFrameOptions& options, const std::vector<float>& radii, RangeFrame& target,
                              RangeFrame& source, const Eigen::Isometry3d& truth) {
  const FrameRegistration one =
      RegisterFrames(target, source, Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp, NicpOptions{});
  const FrameRegistration both = RegisterFramesOverRadii(options, radii, target, source, Eigen::Isometry3d::Identity(),
                                                         RegistrationMethod::kNicp, NicpOptions{});
  EXPECT_TRUE(one.result.ok() && both.result.ok());
  return {testing::PoseErrorOf(one.result.target_T_source, truth),
          testing::PoseErrorOf(both.result.target_T_source, truth), both.result.iterations};
}

// The LiDAR fine radius (docs/benchmarks.md, "Coarse-to-fine statistics radius"): over R =
// 0.3 m alone the four pairs of static sweeps end 0.26-0.83 mm from identity; with the
// last 5 of 10 iterations on normals refitted over 0.05 m, 0.13-0.37 mm.
TEST(NicpRealData, StaticVlp16SweepsLandNearerWithTheLidarFineRadius) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/vlp16_nebula_indoor");
  const std::vector<std::filesystem::path> sweeps = SweepsIn(folder);
  ASSERT_EQ(sweeps.size(), 5U);
  const RangeFrameOptions options;
  double one_radius_sum = 0.0, coarse_to_fine_sum = 0.0;
  for (std::size_t k = 0; k + 1 < sweeps.size(); ++k) {
    RangeFrame target = LoadOrDie(sweeps[k], options);
    RangeFrame source = LoadOrDie(sweeps[k + 1], options);
    const RadiusComparison e = CompareRadii(options, {options.lidar_statistics.radius_m, kLidarFineRadiusM}, target,
                                            source, Eigen::Isometry3d::Identity());
    std::printf("sweeps %zu-%zu: R 0.3 %.3f mm %.4f deg; R 0.3, 0.05 %.3f mm %.4f deg\n", k, k + 1,
                1e3 * e.one_radius.translation_m, e.one_radius.rotation_deg, 1e3 * e.coarse_to_fine.translation_m,
                e.coarse_to_fine.rotation_deg);
    EXPECT_LT(e.coarse_to_fine.translation_m, 0.0005);
    EXPECT_LT(e.coarse_to_fine.rotation_deg, 0.02);
    one_radius_sum += e.one_radius.translation_m;
    coarse_to_fine_sum += e.coarse_to_fine.translation_m;
  }
  EXPECT_LT(coarse_to_fine_sum, 0.6 * one_radius_sum);  // measured 1.09 against 2.17 mm
}

// KITTI poses.txt line i is world_T_cam0(i); calib Tr is cam0_T_velo.
std::vector<Eigen::Isometry3d> KittiVelodynePoses(const std::filesystem::path& folder) {
  std::ifstream calib(folder / "calib.txt");
  std::string line;
  Eigen::Isometry3d cam_T_velo = Eigen::Isometry3d::Identity();
  while (std::getline(calib, line)) {
    if (line.rfind("Tr:", 0) == 0) cam_T_velo = *hal::trajectory::ParseTransform(line.substr(3), "calib.txt Tr");
  }
  std::vector<Eigen::Isometry3d> poses;
  std::ifstream file(folder / "poses.txt");
  while (std::getline(file, line)) poses.push_back(*hal::trajectory::ParseTransform(line, "poses.txt") * cam_T_velo);
  return poses;
}

TEST(NicpRealData, KittiPairsTwelveToFifteenMatchTheTruth) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/kitti_odometry_00_frames_000000-000015");
  const std::vector<Eigen::Isometry3d> world_T_velo = KittiVelodynePoses(folder);
  ASSERT_EQ(world_T_velo.size(), 16U);
  // lidar3d/README.md: the truth's first steps are evenly spaced while the car
  // accelerates, wrong by up to 0.18 m until frame ~12; 30 iterations from identity cross
  // the 0.86 m step the road corridor makes slow to find.
  NicpOptions options;
  options.iterations = 30;
  for (int i = 12; i < 15; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "velodyne/%06d.bin", i);
    const RangeFrame target = LoadOrDie(folder / name);
    std::snprintf(name, sizeof name, "velodyne/%06d.bin", i + 1);
    const RangeFrame source = LoadOrDie(folder / name);
    const FrameRegistration r =
        RegisterFrames(target, source, Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp, options);
    ASSERT_TRUE(r.result.ok());
    const Eigen::Isometry3d truth = world_T_velo[static_cast<std::size_t>(i)].inverse() * world_T_velo[static_cast<std::size_t>(i + 1)];
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, truth);
    std::printf("pair %d-%d: %.3f m %.3f deg (truth step %.3f m)\n", i, i + 1, e.translation_m, e.rotation_deg,
                truth.translation().norm());
    EXPECT_LT(e.translation_m, 0.05);
    EXPECT_LT(e.rotation_deg, 0.25);
  }
}

// bun.conf "bmesh FILE tx ty tz qx qy qz qw": p_world = R(q)^T p + t (PROVENANCE.md).
std::map<std::string, Eigen::Isometry3d> BunnyPoses(const std::filesystem::path& conf) {
  std::map<std::string, Eigen::Isometry3d> poses;
  std::ifstream file(conf);
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream fields(line);
    std::string kind, name;
    double tx, ty, tz, qx, qy, qz, qw;
    if (!(fields >> kind >> name >> tx >> ty >> tz >> qx >> qy >> qz >> qw) || kind != "bmesh") continue;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix().transpose();
    pose.translation() = Eigen::Vector3d(tx, ty, tz);
    poses[name] = pose;
  }
  return poses;
}

Eigen::Vector3d CentroidOf(const maps::range3d::SurfelCloud& cloud) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& p : cloud.points) sum += p.cast<double>();
  return sum / static_cast<double>(cloud.size());
}

TEST(NicpRealData, BunnyScansLandOnTheirAlignment) {
  FLAT2D_REQUIRE_DATA(folder, "lidar3d/stanford_bunny_scans");
  const auto world_T_scan = BunnyPoses(folder / "bun.conf");
  RangeFrameOptions frames;
  frames.unorganized_statistics.radius_m = 0.002F;  // scan spacing ~0.5 mm: R of 4 points
  NicpOptions options;
  options.kdtree_alpha = 0.003F;   // Eq. 6.10's 1/3 is for metre scenes: the bunny is 15 cm
  options.max_distance_m = 0.05F;
  options.iterations = 50;
  // The guess a turntable scanner has: the table's nominal angle about y, centroids aligned.
  struct Pair {
    const char* target;
    const char* source;
    double turntable_deg;
  };
  for (const Pair& pair : {Pair{"bun000.ply", "bun045.ply", 45}, Pair{"bun000.ply", "bun315.ply", -45},
                           Pair{"bun045.ply", "bun090.ply", 45}, Pair{"bun270.ply", "bun315.ply", 45}}) {
    const RangeFrame target = LoadOrDie(folder / pair.target, frames);
    const RangeFrame source = LoadOrDie(folder / pair.source, frames);
    Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
    guess.linear() = Eigen::AngleAxisd(pair.turntable_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    guess.translation() = CentroidOf(target.cloud) - guess.linear() * CentroidOf(source.cloud);
    const FrameRegistration r = RegisterFrames(target, source, guess, RegistrationMethod::kNicp, options);
    ASSERT_TRUE(r.result.ok());
    EXPECT_TRUE(r.kdtree);
    const Eigen::Isometry3d truth = world_T_scan.at(pair.target).inverse() * world_T_scan.at(pair.source);
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, truth);
    const testing::PoseError start = testing::PoseErrorOf(guess, truth);
    std::printf("%s-%s: from %.1f mm %.2f deg to %.2f mm %.3f deg\n", pair.target, pair.source,
                1e3 * start.translation_m, start.rotation_deg, 1e3 * e.translation_m, e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.001) << pair.source;
    EXPECT_LT(e.rotation_deg, 0.25) << pair.source;
  }
}

// TUM's truth is 100 Hz: the pose at a depth stamp, interpolated.
Eigen::Isometry3d TruthAt(const std::vector<hal::trajectory::StampedPose>& truth, double time_s) {
  const auto t = static_cast<TimeNs>(std::llround(time_s * 1e9));
  std::size_t i = 1;
  while (i + 1 < truth.size() && truth[i].time_ns < t) ++i;
  const auto& a = truth[i - 1];
  const auto& b = truth[i];
  const double u = static_cast<double>(t - a.time_ns) / static_cast<double>(b.time_ns - a.time_ns);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(a.world_T_body.linear()).slerp(u, Eigen::Quaterniond(b.world_T_body.linear())).toRotationMatrix();
  pose.translation() = (1.0 - u) * a.world_T_body.translation() + u * b.world_T_body.translation();
  return pose;
}

TEST(NicpRealData, TumDepthPairsMatchTheMotionCapture) {
  FLAT2D_REQUIRE_DATA(folder, "depth/tum_rgbd_fr1_rpy_first200");
  const auto frames = hal::cloud::ReadTumAssociationList(folder / "depth.txt");
  const auto truth = hal::trajectory::ReadTum(folder / "groundtruth.txt");
  ASSERT_TRUE(frames.ok() && truth.ok());
  // Consecutive frames 30 ms apart, fr1/rpy turning 1-4 deg a frame; issue 11's success
  // tolerance for TUM is 3 cm / 1.5 deg.
  for (const std::size_t k : {9U, 72U, 135U}) {
    const RangeFrame target = LoadOrDie((*frames)[k].file);
    const RangeFrame source = LoadOrDie((*frames)[k + 1].file);
    const FrameRegistration r =
        RegisterFrames(target, source, Eigen::Isometry3d::Identity(), RegistrationMethod::kNicp, NicpOptions{});
    ASSERT_TRUE(r.result.ok());
    const Eigen::Isometry3d motion = TruthAt(*truth, (*frames)[k].time_s).inverse() * TruthAt(*truth, (*frames)[k + 1].time_s);
    const testing::PoseError e = testing::PoseErrorOf(r.result.target_T_source, motion);
    const testing::PoseError start = testing::PoseErrorOf(Eigen::Isometry3d::Identity(), motion);
    std::printf("frames %zu-%zu: motion %.1f mm %.2f deg, error %.1f mm %.3f deg\n", k, k + 1,
                1e3 * start.translation_m, start.rotation_deg, 1e3 * e.translation_m, e.rotation_deg);
    EXPECT_LT(e.translation_m, 0.03);
    EXPECT_LT(e.rotation_deg, 1.5);
    EXPECT_LT(e.rotation_deg, 0.5 * start.rotation_deg);  // better than standing still, by far
  }
}

// At the 160x120 working resolution, pairs that R = 0.1 m alone leaves 14-38 mm off
// (docs/benchmarks.md, "Coarse-to-fine statistics radius": pairs 8, 16, 18 and 49 of the
// evaluation) land within a centimetre when the last 5 of the 10 iterations use normals
// refitted over 0.03 m.
TEST(NicpRealData, TumPairsLandNearerWithCoarseToFineRadii) {
  FLAT2D_REQUIRE_DATA(folder, "depth/tum_rgbd_fr1_rpy_first200");
  const auto frames = hal::cloud::ReadTumAssociationList(folder / "depth.txt");
  const auto truth = hal::trajectory::ReadTum(folder / "groundtruth.txt");
  ASSERT_TRUE(frames.ok() && truth.ok());
  RangeFrameOptions options;
  options.image_scale = 4;
  double one_radius_sum = 0.0, coarse_to_fine_sum = 0.0;
  for (const std::size_t k : {32U, 64U, 72U, 196U}) {
    const Eigen::Isometry3d motion = TruthAt(*truth, (*frames)[k].time_s).inverse() * TruthAt(*truth, (*frames)[k + 1].time_s);
    RangeFrame target = LoadOrDie((*frames)[k].file, options);
    RangeFrame source = LoadOrDie((*frames)[k + 1].file, options);
    const RadiusComparison e = CompareRadii(options, {0.1F, kDepthFineRadiusM}, target, source, motion);
    EXPECT_LE(e.coarse_to_fine_iterations, 10);
    EXPECT_FLOAT_EQ(target.statistics_radius_m, kDepthFineRadiusM);
    std::printf("frames %zu-%zu: R 0.1 %.1f mm %.3f deg; R 0.1, 0.03 %.1f mm %.3f deg\n", k, k + 1,
                1e3 * e.one_radius.translation_m, e.one_radius.rotation_deg, 1e3 * e.coarse_to_fine.translation_m,
                e.coarse_to_fine.rotation_deg);
    EXPECT_LT(e.coarse_to_fine.translation_m, 0.01);
    EXPECT_LT(e.coarse_to_fine.rotation_deg, 1.0);
    one_radius_sum += e.one_radius.translation_m;
    coarse_to_fine_sum += e.coarse_to_fine.translation_m;
  }
  EXPECT_LT(coarse_to_fine_sum, 0.5 * one_radius_sum);
}

}  // namespace
}  // namespace flat2d::localization::registration
