// The localizer's configuration file: the shipped file states the built-in defaults (so
// the two cannot drift apart), fields override them, bad values are errors naming them.
#include "localization/localizer/localizer_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "hal/config/text_proto.hpp"

namespace flat2d::localization {
namespace {

Result<LocalizerOptions> FromText(const std::string& text) {
  LocalizerConfig config;
  if (Status parsed = hal::config::ParseTextProto(text, "test.textproto", config); !parsed.ok()) return parsed.error();
  return LocalizerOptionsFrom(config);
}

TEST(LocalizerConfig, TheShippedFileHoldsTheDefaults) {
  auto shipped = LoadLocalizerOptions(std::string(FLAT2D_SOURCE_DIR) + "/packaging/config/localizer/localizer.textproto");
  ASSERT_TRUE(shipped.ok()) << shipped.error().message;
  const LocalizerOptions defaults;
  EXPECT_EQ(shipped->map_window.side_m, defaults.map_window.side_m);
  EXPECT_EQ(shipped->map_window.recentre_m, defaults.map_window.recentre_m);
  EXPECT_EQ(shipped->map_cache_tiles, defaults.map_cache_tiles);
  EXPECT_EQ(shipped->match_viewpoints, defaults.match_viewpoints);
  EXPECT_EQ(shipped->map_prefetch, defaults.map_prefetch);
  EXPECT_EQ(shipped->point_range_m, defaults.point_range_m);
  EXPECT_EQ(shipped->decimation_m, defaults.decimation_m);
  EXPECT_EQ(shipped->max_scan_points, defaults.max_scan_points);
  EXPECT_EQ(shipped->tracking_window.linear, defaults.tracking_window.linear);
  EXPECT_EQ(shipped->tracking_window.angular, defaults.tracking_window.angular);
  EXPECT_EQ(shipped->min_score, defaults.min_score);
  EXPECT_EQ(shipped->min_matched_points, defaults.min_matched_points);
  EXPECT_EQ(shipped->min_match_sigma_m, defaults.min_match_sigma_m);
  EXPECT_EQ(shipped->min_match_sigma_rad, defaults.min_match_sigma_rad);
  EXPECT_EQ(shipped->odometry_sigma_per_m, defaults.odometry_sigma_per_m);
  EXPECT_EQ(shipped->odometry_sigma_rad_per_m, defaults.odometry_sigma_rad_per_m);
  EXPECT_EQ(shipped->null_hypothesis.weight, defaults.null_hypothesis.weight);
  EXPECT_EQ(shipped->null_hypothesis.information_scale, defaults.null_hypothesis.information_scale);
  EXPECT_EQ(shipped->graph.capacity, defaults.graph.capacity);
  EXPECT_EQ(shipped->solve_iterations, defaults.solve_iterations);
  EXPECT_EQ(shipped->degraded_after_ns, defaults.degraded_after_ns);
  EXPECT_EQ(shipped->lost_after_ns, defaults.lost_after_ns);
  EXPECT_EQ(shipped->lost_sigma_m, defaults.lost_sigma_m);
  EXPECT_EQ(shipped->relocalization_radius_m, defaults.relocalization_radius_m);
  EXPECT_EQ(shipped->relocalization_growth, defaults.relocalization_growth);
  EXPECT_EQ(shipped->relocalization_max_radius_m, defaults.relocalization_max_radius_m);
  EXPECT_EQ(shipped->relocalization_min_score, defaults.relocalization_min_score);
  EXPECT_EQ(shipped->relocalization_max_peak_ratio, defaults.relocalization_max_peak_ratio);
  EXPECT_EQ(shipped->max_tracking_window_m, defaults.max_tracking_window_m);
  EXPECT_EQ(shipped->initial_lost_after_ns, defaults.initial_lost_after_ns);
  EXPECT_EQ(shipped->confirm_min_score, defaults.confirm_min_score);
  EXPECT_EQ(shipped->relocalization_confirmations, defaults.relocalization_confirmations);
  EXPECT_EQ(shipped->relocalization_min_matched_points, defaults.relocalization_min_matched_points);
}

TEST(LocalizerConfig, FieldsOverrideTheDefaults) {
  auto options = FromText("tracking_window_m: 0.5\nlost_after_s: 2.5\ngraph_nodes: 40\n");
  ASSERT_TRUE(options.ok()) << options.error().message;
  EXPECT_EQ(options->tracking_window.linear, 0.5);
  EXPECT_EQ(options->lost_after_ns, 2'500'000'000);
  EXPECT_EQ(options->graph.capacity, 40);
  EXPECT_EQ(options->min_score, LocalizerOptions{}.min_score);
}

TEST(LocalizerConfig, BadValuesAreErrorsNamingThem) {
  for (const auto& [text, name] : std::vector<std::pair<std::string, std::string>>{
           {"null_weight: 1.5", "null_weight"},
           {"max_scan_points: 3", "max_scan_points"},
           {"map_cache_tiles: 0", "map_cache_tiles"},
           {"lost_after_s: 0.1", "lost_after"},
           {"map_recentre_m: 60", "recentre_m"},
           {"graph_nodes: 1", "capacity"},
           {"odometry_sigma_per_m: -1", "odometry_sigma_per_m"},
           {"no_such_option: 1", "no_such_option"}}) {
    auto options = FromText(text);
    ASSERT_FALSE(options.ok()) << text;
    EXPECT_NE(options.error().message.find(name), std::string::npos) << text << ": " << options.error().message;
  }
}

}  // namespace
}  // namespace flat2d::localization
