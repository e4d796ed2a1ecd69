#include "maps/features3d/vertical_removal.hpp"

#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace flat2d::maps::features3d {
namespace {

// A 32-row, 8-column image whose column c shows the given points, top row first.
struct TestImage {
  std::vector<Eigen::Vector3f> points;
  range3d::IndexImage image;

  TestImage() { image.Clear(32, 8); }
  void Column(int col, const std::vector<Eigen::Vector3f>& column_points) {
    int row = 0;
    for (const Eigen::Vector3f& p : column_points) {
      image.Set(row++, col, static_cast<std::int32_t>(points.size()), p.norm());
      points.push_back(p);
    }
  }
  int Kept(int col) const {
    int kept = 0;
    for (int row = 0; row < image.rows(); ++row) kept += image.at(row, col) >= 0 ? 1 : 0;
    return kept;
  }
};

VerticalRemovalOptions Options(double radius, unsigned min_points_above) {
  VerticalRemovalOptions options;
  options.set_enabled(true);
  options.set_ground_radius_m(radius);
  options.set_min_points_above(min_points_above);
  return options;
}

std::vector<Eigen::Vector3f> Stack(float x, int count, float offset_per_point = 0.0F) {
  std::vector<Eigen::Vector3f> stack;
  for (int k = 0; k < count; ++k) {
    stack.emplace_back(x + offset_per_point * static_cast<float>(k), 0.5F, 1.0F - 0.4F * static_cast<float>(k));
  }
  return stack;
}

TEST(VerticalRemoval, KeepsStacksAndRemovesTheGround) {
  TestImage t;
  t.Column(0, Stack(6.0F, 6));                                                  // a wall's column
  t.Column(1, {{3.3F, 0, -1.9F}, {3.6F, 0, -1.9F}, {4.0F, 0, -1.9F}, {4.6F, 0, -1.9F}, {5.5F, 0, -1.9F}});  // ground rings
  t.Column(2, Stack(8.0F, 6, 0.3F));                                            // a slope: 0.3 m apart
  VerticalRemoval removal(Options(0.1, 2));
  const std::size_t kept = removal.Apply(t.points, Eigen::Vector3f::UnitZ(), t.image);
  EXPECT_EQ(t.Kept(0), 6);
  EXPECT_EQ(t.Kept(1), 0);
  EXPECT_EQ(t.Kept(2), 0);
  EXPECT_EQ(kept, 6U);
  for (int row = 0; row < 5; ++row) EXPECT_FALSE(std::isfinite(t.image.depth(row, 1)));  // removed = empty pixel
}

// eps_t counts the points below: a stack needs more than eps_t of them under its top.
TEST(VerticalRemoval, ThresholdIsStrict) {
  TestImage t;
  t.Column(0, Stack(5.0F, 3));  // top sees 2 below: not > 2
  t.Column(1, Stack(5.0F, 4));  // top sees 3
  VerticalRemoval removal(Options(0.1, 2));
  removal.Apply(t.points, Eigen::Vector3f::UnitZ(), t.image);
  EXPECT_EQ(t.Kept(0), 0);
  EXPECT_EQ(t.Kept(1), 4);
}

// Gravity comes from the mounting: a sensor rolled 90 deg sees walls along its y axis.
TEST(VerticalRemoval, UsesTheGivenUpDirection) {
  const Eigen::Matrix3f sensor_R_world = Eigen::AngleAxisf(1.5707963F, Eigen::Vector3f::UnitX()).toRotationMatrix();
  TestImage level, rolled;
  level.Column(0, Stack(6.0F, 5));
  std::vector<Eigen::Vector3f> turned;
  for (const Eigen::Vector3f& p : Stack(6.0F, 5)) turned.push_back(sensor_R_world * p);
  rolled.Column(0, turned);
  VerticalRemoval removal(Options(0.1, 2));
  removal.Apply(level.points, Eigen::Vector3f::UnitZ(), level.image);
  EXPECT_EQ(level.Kept(0), 5);
  removal.Apply(rolled.points, Eigen::Vector3f::UnitZ(), rolled.image);  // wrong up: a horizontal row
  EXPECT_EQ(rolled.Kept(0), 0);
  TestImage again;
  again.Column(0, turned);
  removal.Apply(again.points, sensor_R_world * Eigen::Vector3f::UnitZ(), again.image);
  EXPECT_EQ(again.Kept(0), 5);
}

}  // namespace
}  // namespace flat2d::maps::features3d
