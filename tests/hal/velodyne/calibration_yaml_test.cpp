#include "hal/velodyne/calibration_yaml.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hal/common/angles.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::hal::velodyne {
namespace {

// One flow-style laser entry per line, as the ROS files write them; `extra` ends the map.
std::string Laser(int id, double rot_correction, const std::string& extra = "") {
  return "- {laser_id: " + std::to_string(id) + ", rot_correction: " +
         std::to_string(rot_correction) + ", vert_correction: " + std::to_string(0.01 * id) +
         extra + "}\n";
}

// `count` lasers on lines 2..count+1, then num_lasers and distance_resolution.
std::string Calibration(int count, double rot_correction = 0.0) {
  std::string text = "lasers:\n";
  for (int id = 0; id < count; ++id) text += Laser(id, rot_correction);
  return text + "num_lasers: " + std::to_string(count) + "\ndistance_resolution: 0.002\n";
}

// 16 lasers where `first_entry` (one line) replaces laser 0.
std::string SixteenWithFirst(const std::string& first_entry) {
  std::string text = "lasers:\n" + first_entry + "\n";
  for (int id = 1; id < 16; ++id) text += Laser(id, 0.0);
  return text;
}

TEST(CalibrationYaml, MapsEveryFieldAndKeepsMissingOnesZero) {
  std::string text = "lasers:\n";
  for (int id = 15; id >= 0; --id) {  // reverse order: the table is indexed by laser_id
    text += id == 3 ? "- {laser_id: 3, rot_correction: 0.01, vert_correction: 0.05,\n"
                      "   dist_correction: 0.021, vert_offset_correction: 0.0112,\n"
                      "   horiz_offset_correction: -0.0026, dist_correction_x: 0.5,\n"
                      "   dist_correction_y: 0.4, focal_distance: 10, focal_slope: 1.2,\n"
                      "   min_intensity: 3, max_intensity: 250,\n"
                      "   two_pt_correction_available: false}\n"
                    : "- {laser_id: " + std::to_string(id) + "}\n";
  }
  const auto table = ParseCalibrationYaml(text, "inline.yaml", std::nullopt);
  ASSERT_TRUE(table.ok()) << table.error().message;
  EXPECT_EQ(table->num_lasers, 16);
  EXPECT_EQ(table->model, Model::kVlp16);
  EXPECT_DOUBLE_EQ(table->distance_resolution_m, 0.002);  // VLP-16 default, not in the file
  const LaserCorrection& laser = table->lasers[3];
  EXPECT_DOUBLE_EQ(laser.rot_correction_rad, 0.01);
  EXPECT_DOUBLE_EQ(laser.elevation_rad, 0.05);
  EXPECT_DOUBLE_EQ(laser.distance_offset_m, 0.021);
  EXPECT_DOUBLE_EQ(laser.vertical_offset_m, 0.0112);
  EXPECT_DOUBLE_EQ(laser.horizontal_offset_m, -0.0026);
  const LaserCorrection& bare = table->lasers[4];
  EXPECT_EQ(bare.elevation_rad, 0.0);
  EXPECT_EQ(bare.rot_correction_rad, 0.0);
  EXPECT_EQ(bare.distance_offset_m, 0.0);
  EXPECT_EQ(bare.vertical_offset_m, 0.0);
  EXPECT_EQ(bare.horizontal_offset_m, 0.0);
}

TEST(CalibrationYaml, InfersThe32LaserModelFromRotCorrection) {
  const auto hdl = ParseCalibrationYaml(Calibration(32, 0.0), "a.yaml", std::nullopt);
  ASSERT_TRUE(hdl.ok()) << hdl.error().message;
  EXPECT_EQ(hdl->model, Model::kHdl32e);
  std::string vlp32_text = Calibration(32, 0.0);
  vlp32_text.replace(vlp32_text.find("rot_correction: 0.000000"), 24, "rot_correction: -0.0244");
  const auto vlp32 = ParseCalibrationYaml(vlp32_text, "b.yaml", std::nullopt);
  ASSERT_TRUE(vlp32.ok()) << vlp32.error().message;
  EXPECT_EQ(vlp32->model, Model::kVlp32c);
  EXPECT_DOUBLE_EQ(vlp32->lasers[0].rot_correction_rad, -0.0244);
  EXPECT_DOUBLE_EQ(vlp32->lasers[31].elevation_rad, 0.31);
  EXPECT_DOUBLE_EQ(vlp32->distance_resolution_m, 0.002);  // the file's value wins
}

TEST(CalibrationYaml, GivenModelWinsWhenTheCountMatches) {
  const auto table = ParseCalibrationYaml(Calibration(32), "c.yaml", Model::kVlp32c);
  ASSERT_TRUE(table.ok()) << table.error().message;
  EXPECT_EQ(table->model, Model::kVlp32c);
  const auto mismatch = ParseCalibrationYaml(Calibration(32), "c.yaml", Model::kVlp16);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_EQ(mismatch.error().message,
            "c.yaml: calibration has 32 lasers but the model VLP-16 has 16");
}

struct BadCalibration {
  std::string text;
  std::vector<std::string> in_message;
};

std::vector<BadCalibration> BadCalibrations() {
  std::string missing_id = Calibration(16);
  missing_id.replace(missing_id.find("laser_id: 2,"), 12, "");
  std::string duplicate = Calibration(16);
  duplicate.replace(duplicate.find("laser_id: 2,"), 12, "laser_id: 1,");
  std::string out_of_range = Calibration(16);
  out_of_range.replace(out_of_range.find("laser_id: 5,"), 12, "laser_id: 16,");
  std::string wrong_count = Calibration(16);
  wrong_count.replace(wrong_count.find("num_lasers: 16"), 14, "num_lasers: 32");
  std::string fractional_id = Calibration(16);
  fractional_id.replace(fractional_id.find("laser_id: 1,"), 12, "laser_id: 1.5,");
  std::string no_lasers_16 = "lasers:\n";
  for (int id = 0; id < 16; ++id) no_lasers_16 += "- {laser_id: " + std::to_string(id) + "}\n";
  return {
      {missing_id, {"t.yaml:4: ", "list index 2", "missing laser_id"}},
      {duplicate, {"t.yaml:4: ", "list index 2", "duplicate laser_id 1", "first at list index 1"}},
      {out_of_range, {"t.yaml:7: ", "list index 5", "laser_id '16'", "0..15"}},
      {wrong_count, {"t.yaml:18: ", "num_lasers 32", "16 entries"}},
      {SixteenWithFirst("- 3"), {"t.yaml:2: ", "list index 0", "expected a map"}},
      {fractional_id, {"list index 1", "laser_id '1.5'"}},
      {SixteenWithFirst("- {laser_id: 0, vert_corection: 0.1}"),
       {"t.yaml:2: ", "list index 0", "unknown key 'vert_corection'"}},
      {no_lasers_16 + "model: VLP-16\n", {"t.yaml:18: ", "unknown key 'model'"}},
      {SixteenWithFirst("- {laser_id: 0, dist_correction: abc}"),
       {"t.yaml:2: ", "list index 0", "laser_id 0", "dist_correction", "'abc'"}},
      {SixteenWithFirst("- {laser_id: 0, focal_slope: .nan}"), {"focal_slope", "finite"}},
      {SixteenWithFirst("- {laser_id: 0, vert_correction: -15}"), {"vert_correction", "radians"}},
      {SixteenWithFirst("- {laser_id: 0, rot_correction: 4}"), {"rot_correction", "radians"}},
      {SixteenWithFirst("- {laser_id: 0, two_pt_correction_available: 7}"), {"true or false"}},
      {"lasers:\n- {laser_id: 0, vert_correction: [1, 2}\n", {"t.yaml:2", "YAML error"}},
      {"- 1\n- 2\n", {"t.yaml: expected a YAML map"}},
      {"", {"t.yaml: expected a YAML map"}},
      {"num_lasers: 16\n", {"missing 'lasers'"}},
      {"lasers: 3\n", {"'lasers' is not a list"}},
      {Calibration(8),
       {"t.yaml: calibration has 8 lasers; flat2d supports VLP-16, HDL-32E, VLP-32C"}},
      {no_lasers_16 + "distance_resolution: -1\n", {"distance_resolution must be positive"}},
  };
}

TEST(CalibrationYaml, ErrorsNameFileLineLaserAndField) {
  for (const BadCalibration& bad : BadCalibrations()) {
    const auto table = ParseCalibrationYaml(bad.text, "t.yaml", std::nullopt);
    ASSERT_FALSE(table.ok()) << "accepted:\n" << bad.text;
    for (const std::string& part : bad.in_message) {
      EXPECT_NE(table.error().message.find(part), std::string::npos)
          << "expected '" << part << "' in: " << table.error().message;
    }
  }
}

TEST(CalibrationYaml, TruncatedAndDeeplyNestedTextNeverCrashes) {
  const std::string text = Calibration(16);
  int accepted = 0;
  for (std::size_t length = 0; length < text.size(); length += 7) {
    accepted += ParseCalibrationYaml(text.substr(0, length), "cut.yaml", std::nullopt).ok();
  }
  // Only cuts after the 16th laser (in the num_lasers / distance_resolution lines) parse.
  EXPECT_LT(accepted, 10);
  const auto deep = ParseCalibrationYaml("lasers: " + std::string(100'000, '['), "deep.yaml",
                                         std::nullopt);
  ASSERT_FALSE(deep.ok());
  EXPECT_NE(deep.error().message.find("deep.yaml"), std::string::npos) << deep.error().message;
}

TEST(CalibrationYaml, MissingFileIsAnErrorNamingIt) {
  const auto table = LoadCalibrationYaml("/nonexistent/calib.yaml", std::nullopt);
  ASSERT_FALSE(table.ok());
  EXPECT_EQ(table.error().message, "/nonexistent/calib.yaml: cannot open calibration file");
}

// The driver files carry the manual's printed elevations (VLP-16 Table 9-1 whole degrees,
// HDL-32E 0.01 deg, VLP-32C Table 9-1 0.001 deg) converted to radians; 1e-6 deg is far
// inside that rounding and still catches any laser that is off by one in the table.
constexpr double kElevationToleranceDeg = 1e-6;

struct RealFile {
  const char* name;
  Model model;
};

TEST(CalibrationYaml, DriverFilesMatchTheManualTables) {
  const RealFile files[] = {
      {"ros-velodyne_VLP16db.yaml", Model::kVlp16},
      {"nebula_VLP16.yaml", Model::kVlp16},
      {"ros-velodyne_32db.yaml", Model::kHdl32e},
      {"nebula_HDL32.yaml", Model::kHdl32e},
      {"ros-velodyne_VeloView-VLP-32C.yaml", Model::kVlp32c},
      {"nebula_VLP32.yaml", Model::kVlp32c},
  };
  FLAT2D_REQUIRE_DATA(first, "velodyne/calibration/ros-velodyne_VLP16db.yaml");
  for (const RealFile& file : files) {
    const auto path = first.parent_path() / file.name;
    const auto table = LoadCalibrationYaml(path, std::nullopt);
    ASSERT_TRUE(table.ok()) << table.error().message;
    EXPECT_EQ(table->model, file.model) << file.name;
    const LaserTable manual = DefaultLaserTable(file.model);
    ASSERT_EQ(table->num_lasers, manual.num_lasers) << file.name;
    EXPECT_DOUBLE_EQ(table->distance_resolution_m, manual.distance_resolution_m) << file.name;
    for (int id = 0; id < table->num_lasers; ++id) {
      const auto index = static_cast<std::size_t>(id);
      EXPECT_NEAR(table->lasers[index].elevation_rad * kRadToDeg,
                  ManualElevationDeg(file.model, id), kElevationToleranceDeg)
          << file.name << " laser " << id;
      // VLP-32C azimuth offsets: the manual prints 1.4 and 4.2 deg; within 0.01 deg.
      EXPECT_NEAR(table->lasers[index].rot_correction_rad * kRadToDeg,
                  manual.lasers[index].rot_correction_rad * kRadToDeg, 0.01)
          << file.name << " laser " << id;
    }
  }
}

TEST(CalibrationYaml, PuckHiResFileLoadsAsA16LaserTableWithItsOwnElevations) {
  FLAT2D_REQUIRE_DATA(path, "velodyne/calibration/ros-velodyne_VLP16_hires_db.yaml");
  const auto table = LoadCalibrationYaml(path, std::nullopt);
  ASSERT_TRUE(table.ok()) << table.error().message;
  EXPECT_EQ(table->model, Model::kVlp16);
  // Puck Hi-Res: +-10 deg in 4/3 deg steps, interleaved like the VLP-16.
  EXPECT_NEAR(table->lasers[0].elevation_rad * kRadToDeg, -10.0, 1e-6);
  EXPECT_NEAR(table->lasers[1].elevation_rad * kRadToDeg, 2.0 / 3.0, 1e-4);
  EXPECT_NEAR(table->lasers[15].elevation_rad * kRadToDeg, 10.0, 1e-6);
}

TEST(CalibrationYaml, SixtyFourAndOneTwentyEightLaserFilesAreRefused) {
  const std::pair<const char*, int> files[] = {
      {"ros-velodyne_64e_s2.1-sztaki.yaml", 64}, {"ros-velodyne_64e_s3-xiesc.yaml", 64},
      {"ros-velodyne_64e_utexas.yaml", 64},      {"nebula_HDL64e_s3.yaml", 64},
      {"ros-velodyne_VLS128.yaml", 128},         {"nebula_VLS128.yaml", 128},
  };
  FLAT2D_REQUIRE_DATA(first, "velodyne/calibration/ros-velodyne_64e_utexas.yaml");
  for (const auto& [name, count] : files) {
    const auto path = first.parent_path() / name;
    // Also with a model given: the count is checked first.
    const std::optional<Model> models[] = {std::nullopt, Model::kHdl32e};
    for (const std::optional<Model>& model : models) {
      const auto table = LoadCalibrationYaml(path, model);
      ASSERT_FALSE(table.ok()) << name;
      EXPECT_EQ(table.error().message,
                path.string() + ": calibration has " + std::to_string(count) +
                    " lasers; flat2d supports VLP-16, HDL-32E, VLP-32C");
    }
  }
}

}  // namespace
}  // namespace flat2d::hal::velodyne
