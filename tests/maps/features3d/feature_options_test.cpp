#include "maps/features3d/feature_options.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace flat2d::maps::features3d {
namespace {

const std::filesystem::path kShipped = std::filesystem::path(FLAT2D_SOURCE_DIR) / "packaging/config/features3d/features3d.textproto";

std::filesystem::path WriteTemp(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

TEST(FeatureOptions, ShippedConfigLoadsAndIsValid) {
  auto options = LoadFeatureOptions(kShipped);
  ASSERT_TRUE(options.ok()) << options.error().message;
  EXPECT_TRUE(options->vertical().enabled());
  EXPECT_GT(options->segmentation().min_normal_dot(), 0.0);
  EXPECT_EQ(options->segmentation().join(), SegmentationOptions::BOTH);  // Algorithm 8's rule
}

TEST(FeatureOptions, EachBadValueIsNamed) {
  auto valid = LoadFeatureOptions(kShipped);
  ASSERT_TRUE(valid.ok());
  struct Case {
    void (*spoil)(FeatureExtractionOptions&);
    const char* field;
  };
  const Case cases[] = {
      {[](FeatureExtractionOptions& o) { o.mutable_vertical()->set_ground_radius_m(0.0); }, "vertical.ground_radius_m"},
      {[](FeatureExtractionOptions& o) { o.mutable_normals()->set_min_points(2); }, "normals.min_points"},
      {[](FeatureExtractionOptions& o) { o.mutable_normals()->set_depth_jump_ratio(1.5); }, "normals.depth_jump_ratio"},
      {[](FeatureExtractionOptions& o) { o.mutable_segmentation()->set_min_normal_dot(1.5); }, "segmentation.min_normal_dot"},
      {[](FeatureExtractionOptions& o) { o.mutable_segmentation()->set_max_distance_per_m(-1.0); },
       "segmentation.max_distance_per_m"},
      {[](FeatureExtractionOptions& o) { o.mutable_segmentation()->set_pole_max_width_m(-0.5); }, "segmentation.pole_max_width_m"},
      {[](FeatureExtractionOptions& o) { o.mutable_segmentation()->set_pole_join_distance_m(-0.1); },
       "segmentation.pole_join_distance_m"},
      {[](FeatureExtractionOptions& o) { o.mutable_fitting()->set_line_max_spread(0.0); }, "fitting.line_max_spread"},
      {[](FeatureExtractionOptions& o) { o.mutable_fitting()->set_line_min_roundness(1.0); }, "fitting.line_min_roundness"},
      {[](FeatureExtractionOptions& o) { o.mutable_fitting()->set_line_axis_min_radius_m(-0.1); },
       "fitting.line_axis_min_radius_m"},
      {[](FeatureExtractionOptions& o) { o.mutable_fitting()->set_min_plane_height_m(-1.0); },
       "fitting.min_plane_height_m"},
      {[](FeatureExtractionOptions& o) { o.set_columns(10); }, "columns"},
      {[](FeatureExtractionOptions& o) { o.set_rotation_rpm(-600.0); }, "rotation_rpm"},
      {[](FeatureExtractionOptions& o) { o.set_rotation_rpm(3000.0); }, "rotation_rpm"},
      {[](FeatureExtractionOptions& o) { (*o.mutable_vertical()->mutable_min_points_above_by_sensor())["vlp64"] = 2; },
       "vertical.min_points_above_by_sensor"},
      {[](FeatureExtractionOptions& o) { (*o.mutable_vertical()->mutable_min_points_above_by_sensor())["pinhole"] = 2; },
       "vertical.min_points_above_by_sensor"},
      {[](FeatureExtractionOptions& o) { (*o.mutable_vertical()->mutable_min_points_above_by_sensor())["hdl32e"] = 0; },
       "vertical.min_points_above_by_sensor"},
  };
  for (const Case& c : cases) {
    FeatureExtractionOptions options = *valid;
    c.spoil(options);
    const Status status = ValidateFeatureOptions(options);
    ASSERT_FALSE(status.ok()) << c.field;
    EXPECT_EQ(status.error().message.rfind(c.field, 0), 0U) << status.error().message;
  }
}

// The shipped file gives the VLP-16 its own eps_t; the other LiDARs keep the common one.
TEST(FeatureOptions, SensorEntriesReplaceTheRemovalThreshold) {
  auto shipped = LoadFeatureOptions(kShipped);
  ASSERT_TRUE(shipped.ok());
  const unsigned common = shipped->vertical().min_points_above();
  EXPECT_EQ(OptionsForSensor(*shipped, range3d::SensorModel::kVlp16).vertical().min_points_above(), 1U);
  for (const auto sensor : {range3d::SensorModel::kHdl32e, range3d::SensorModel::kVlp32c, range3d::SensorModel::kKitti64}) {
    EXPECT_EQ(OptionsForSensor(*shipped, sensor).vertical().min_points_above(), common)
        << range3d::SensorModelName(sensor);
  }
  FeatureExtractionOptions options = *shipped;
  (*options.mutable_vertical()->mutable_min_points_above_by_sensor())["kitti64"] = 5;
  ASSERT_TRUE(ValidateFeatureOptions(options).ok());
  EXPECT_EQ(OptionsForSensor(options, range3d::SensorModel::kKitti64).vertical().min_points_above(), 5U);
  EXPECT_EQ(OptionsForSensor(options, range3d::SensorModel::kKitti64).segmentation().min_rows(),
            shipped->segmentation().min_rows());
}

TEST(FeatureOptions, UnknownFieldFailsWithFileAndLine) {
  const auto path = WriteTemp("flat2d_features_unknown.textproto", "vertical { enabled: true }\nsegmentaton {}\n");
  auto options = LoadFeatureOptions(path);
  ASSERT_FALSE(options.ok());
  EXPECT_NE(options.error().message.find("flat2d_features_unknown.textproto:2"), std::string::npos)
      << options.error().message;
}

TEST(FeatureOptions, MissingThresholdsAreRejected) {
  const auto path = WriteTemp("flat2d_features_empty.textproto", "max_range_m: 20\n");
  auto options = LoadFeatureOptions(path);
  ASSERT_FALSE(options.ok());
  EXPECT_NE(options.error().message.find("vertical.ground_radius_m"), std::string::npos) << options.error().message;
}

}  // namespace
}  // namespace flat2d::maps::features3d
