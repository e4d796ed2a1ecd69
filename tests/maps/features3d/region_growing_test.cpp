#include "maps/features3d/region_growing.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace flat2d::maps::features3d {
namespace {

SegmentationOptions Options(SegmentationOptions::JoinRule join) {
  SegmentationOptions options;
  options.set_max_distance_m(0.3);
  options.set_max_distance_per_m(0.0);
  options.set_min_normal_dot(0.9);
  options.set_min_cluster_points(3);
  options.set_join(join);
  options.set_neighbour_cols(1);
  options.set_min_rows(0);
  return options;
}

// Pixels (row, col) showing points with normals, the rest empty.
struct TestCloud {
  range3d::IndexImage image;
  range3d::SurfelCloud cloud;
  TestCloud() { image.Clear(4, 20); }
  void Add(int row, int col, const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
    image.Set(row, col, static_cast<std::int32_t>(cloud.points.size()), p.norm());
    cloud.points.push_back(p);
    cloud.normals.push_back(n);
    cloud.curvature.push_back(0.0F);
    cloud.disc_gain.push_back(0.0F);
  }
};

// Two walls meeting at a corner: columns 0-7 face x, 8-15 face y, 0.1 m apart in space.
TestCloud Corner() {
  TestCloud t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 16; ++col) {
      const bool first = col < 8;
      const float s = 0.1F * static_cast<float>(col);
      const Eigen::Vector3f p(first ? 5.0F : 5.0F - (s - 0.8F), first ? s : 0.8F, 0.2F * static_cast<float>(row));
      t.Add(row, col, p, first ? Eigen::Vector3f(-1, 0, 0) : Eigen::Vector3f(0, -1, 0));
    }
  }
  return t;
}

TEST(RegionGrowing, BothRuleSplitsAtTheCorner) {
  const TestCloud t = Corner();
  RegionGrowing segmentation(Options(SegmentationOptions::BOTH));
  const Clusters& clusters = segmentation.Segment(t.image, t.cloud);
  ASSERT_EQ(clusters.size(), 2U);
  EXPECT_EQ(clusters.size_of(0), 24U);
  EXPECT_EQ(clusters.size_of(1), 24U);
  for (std::size_t i = clusters.begin[0]; i < clusters.begin[1]; ++i) {
    EXPECT_LT(t.cloud.points[static_cast<std::size_t>(clusters.points[i])].y(), 0.75F);  // all of the first wall
  }
}

// The text's rule: nearness alone joins the walls.
TEST(RegionGrowing, EitherRuleJoinsNearPoints) {
  const TestCloud t = Corner();
  RegionGrowing segmentation(Options(SegmentationOptions::EITHER));
  const Clusters& clusters = segmentation.Segment(t.image, t.cloud);
  ASSERT_EQ(clusters.size(), 1U);
  EXPECT_EQ(clusters.size_of(0), 48U);
}

// A moving seed follows a long wall whose ends are much farther apart than eps_d.
// A thin post: 2 columns x 4 rows whose normals turn about the post from pixel to pixel (a
// neighbourhood that is a line fixes no normal). Eq. 8.3 joins no two of them; with their
// line directions, vertical give or take a few degrees, the post is one cluster.
TEST(RegionGrowing, LineDirectionsJoinAThinPostWhoseNormalsTurn) {
  TestCloud t;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 2; ++col) {
      const float turn = 0.6F * static_cast<float>(2 * row + col);  // 34 deg between neighbours
      t.Add(row, col, {8.0F, 0.04F * static_cast<float>(col), 1.0F - 0.15F * static_cast<float>(row)},
            {-std::cos(turn), std::sin(turn), 0.0F});
    }
  }
  RegionGrowing segmentation(Options(SegmentationOptions::BOTH));
  EXPECT_EQ(segmentation.Segment(t.image, t.cloud).size(), 0U);  // every piece below eps_c

  t.cloud.line_directions.assign(t.cloud.size(), Eigen::Vector3f::Zero());
  for (std::size_t i = 0; i < t.cloud.size(); ++i) {
    const float tilt = 0.03F * static_cast<float>(i % 3) * (i % 2 == 0 ? 1.0F : -1.0F);  // up to 3.4 deg
    t.cloud.line_directions[i] = Eigen::Vector3f(tilt, 0.0F, i % 2 == 0 ? 1.0F : -1.0F).normalized();  // sign free
  }
  const Clusters& clusters = segmentation.Segment(t.image, t.cloud);
  ASSERT_EQ(clusters.size(), 1U);
  EXPECT_EQ(clusters.size_of(0), 8U);

  // A point whose neighbourhood is no line is judged by its normal, as before.
  t.cloud.line_directions[3] = Eigen::Vector3f::Zero();
  const Clusters& split = segmentation.Segment(t.image, t.cloud);
  ASSERT_EQ(split.size(), 1U);
  EXPECT_EQ(split.size_of(0), 7U);
}

TEST(RegionGrowing, MovingSeedGrowsAlongAWall) {
  TestCloud t;
  for (int col = 0; col < 20; ++col) t.Add(1, col, {4.0F, 0.25F * static_cast<float>(col), 0.0F}, {-1, 0, 0});
  RegionGrowing segmentation(Options(SegmentationOptions::BOTH));
  const Clusters& clusters = segmentation.Segment(t.image, t.cloud);
  ASSERT_EQ(clusters.size(), 1U);
  EXPECT_EQ(clusters.size_of(0), 20U);
}

// Clusters of eps_c points or fewer are dropped; points without a normal join nothing; the
// azimuth wraps round from the last column to the first.
TEST(RegionGrowing, DropsSmallClustersSkipsUndefinedNormalsAndWraps) {
  TestCloud t;
  for (int col : {18, 19, 0, 1}) t.Add(0, col, {4.0F, 0.05F * static_cast<float>((col + 2) % 20), 0.0F}, {-1, 0, 0});
  t.Add(2, 10, {3.0F, 1.0F, 0.0F}, {-1, 0, 0});  // alone
  t.Add(2, 11, {3.0F, 1.05F, 0.0F}, {0, 0, 0});  // no normal
  t.Add(2, 12, {3.0F, 1.10F, 0.0F}, {-1, 0, 0});
  RegionGrowing segmentation(Options(SegmentationOptions::BOTH));
  const Clusters& clusters = segmentation.Segment(t.image, t.cloud);
  ASSERT_EQ(clusters.size(), 1U);
  EXPECT_EQ(clusters.size_of(0), 4U);
}

// The visible half of a 0.2 m trunk 18.9 m away, `rows` rows x 6 columns, whose normals turn
// 30 deg from column to column (a far pole: d * da / r), more than eps_n (0.9) allows.
TestCloud FarTrunk(int rows) {
  TestCloud t;
  constexpr float kPi = 3.14159265F;
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < 6; ++col) {
      const float theta = (-75.0F + 30.0F * static_cast<float>(col)) * kPi / 180.0F;
      t.Add(row, 4 + col, {18.9F - 0.2F * std::cos(theta), 0.2F * std::sin(theta), 1.2F - 0.25F * static_cast<float>(row)},
            {-std::cos(theta), std::sin(theta), 0.0F});
    }
  }
  return t;
}

SegmentationOptions PoleJoining(SegmentationOptions options) {
  options.set_pole_max_width_m(0.5);
  options.set_pole_join_distance_m(0.3);
  options.set_pole_min_piece_points(2);
  return options;
}

TEST(RegionGrowing, PoleJoiningRejoinsAFarTrunkCutByItsTurningNormals) {
  const TestCloud t = FarTrunk(4);
  RegionGrowing algorithm8(Options(SegmentationOptions::BOTH));
  const Clusters& strips = algorithm8.Segment(t.image, t.cloud);
  ASSERT_EQ(strips.size(), 6U);  // one per column
  for (std::size_t k = 0; k < strips.size(); ++k) EXPECT_EQ(strips.size_of(k), 4U);

  RegionGrowing joined(PoleJoining(Options(SegmentationOptions::BOTH)));
  const Clusters& trunk = joined.Segment(t.image, t.cloud);
  ASSERT_EQ(trunk.size(), 1U);
  EXPECT_EQ(trunk.size_of(0), 24U);
}

// Pieces too wide together for a pole keep Algorithm 8's cut: two walls at a corner.
TEST(RegionGrowing, PoleJoiningLeavesWallsAtACornerApart) {
  const TestCloud t = Corner();
  RegionGrowing segmentation(PoleJoining(Options(SegmentationOptions::BOTH)));
  EXPECT_EQ(segmentation.Segment(t.image, t.cloud).size(), 2U);
}

// Single returns (foliage) and points further apart than the join distance stay pieces.
TEST(RegionGrowing, PoleJoiningNeedsPiecesOfTwoPointsThatTouch) {
  SegmentationOptions options = PoleJoining(Options(SegmentationOptions::BOTH));
  const TestCloud ring = FarTrunk(1);  // one point per piece
  RegionGrowing two_points(options);
  EXPECT_EQ(two_points.Segment(ring.image, ring.cloud).size(), 0U);
  options.set_pole_min_piece_points(1);
  RegionGrowing one_point(options);
  const Clusters& joined = one_point.Segment(ring.image, ring.cloud);
  ASSERT_EQ(joined.size(), 1U);
  EXPECT_EQ(joined.size_of(0), 6U);

  options.set_pole_join_distance_m(0.05);  // under the 0.10 m between columns
  RegionGrowing apart(options);
  EXPECT_EQ(apart.Segment(ring.image, ring.cloud).size(), 0U);
}

}  // namespace
}  // namespace flat2d::maps::features3d
