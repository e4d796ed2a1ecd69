#include "localization/localizer/localizer_config.hpp"

#include <algorithm>

#include "hal/config/text_proto.hpp"

namespace flat2d::localization {
namespace {

TimeNs Nanoseconds(double seconds) { return static_cast<TimeNs>(seconds * 1e9); }

}  // namespace

Result<LocalizerOptions> LocalizerOptionsFrom(const LocalizerConfig& c) {
  LocalizerOptions o;
  if (c.has_map_window_m()) o.map_window.side_m = c.map_window_m();
  if (c.has_map_recentre_m()) o.map_window.recentre_m = c.map_recentre_m();
  if (c.has_map_prefetch()) o.map_prefetch = c.map_prefetch();
  if (c.has_map_cache_tiles()) {
    if (c.map_cache_tiles() < 1) return MakeError("map_cache_tiles must be >= 1");
    o.map_cache_tiles = c.map_cache_tiles();
  }
  if (c.has_match_viewpoints()) o.match_viewpoints = c.match_viewpoints();
  if (c.has_point_range_m()) o.point_range_m = c.point_range_m();
  if (c.has_decimation_m()) o.decimation_m = c.decimation_m();
  if (c.has_max_scan_points()) {
    if (c.max_scan_points() < 20) return MakeError("max_scan_points must be >= 20");
    o.max_scan_points = static_cast<std::size_t>(c.max_scan_points());
  }
  if (c.has_tracking_window_m()) o.tracking_window.linear = c.tracking_window_m();
  if (c.has_tracking_window_rad()) o.tracking_window.angular = c.tracking_window_rad();
  if (c.has_confirm_min_score()) o.confirm_min_score = c.confirm_min_score();
  if (c.has_relocalization_min_matched_points()) {
    if (c.relocalization_min_matched_points() < 0) return MakeError("relocalization_min_matched_points must be >= 0");
    o.relocalization_min_matched_points = static_cast<std::size_t>(c.relocalization_min_matched_points());
  }
  if (c.has_max_tracking_window_m()) o.max_tracking_window_m = c.max_tracking_window_m();
  if (c.has_min_score()) o.min_score = c.min_score();
  if (c.has_min_matched_points()) {
    if (c.min_matched_points() < 0) return MakeError("min_matched_points must be >= 0");
    o.min_matched_points = static_cast<std::size_t>(c.min_matched_points());
  }
  if (c.has_min_match_sigma_m()) o.min_match_sigma_m = c.min_match_sigma_m();
  if (c.has_min_match_sigma_rad()) o.min_match_sigma_rad = c.min_match_sigma_rad();
  if (c.has_odometry_sigma_per_m()) o.odometry_sigma_per_m = c.odometry_sigma_per_m();
  if (c.has_odometry_sigma_rad_per_m()) o.odometry_sigma_rad_per_m = c.odometry_sigma_rad_per_m();
  if (c.has_null_weight()) o.null_hypothesis.weight = c.null_weight();
  if (c.has_null_information_scale()) o.null_hypothesis.information_scale = c.null_information_scale();
  if (!(o.null_hypothesis.weight > 0.0 && o.null_hypothesis.weight < 1.0) ||
      !(o.null_hypothesis.information_scale > 0.0 && o.null_hypothesis.information_scale < 1.0)) {
    return MakeError("null_weight and null_information_scale must be in (0, 1)");
  }
  if (c.has_graph_nodes()) o.graph.capacity = c.graph_nodes();
  if (c.has_marginalize_oldest()) o.graph.marginalize = c.marginalize_oldest();
  if (c.has_solve_iterations()) o.solve_iterations = c.solve_iterations();
  if (c.has_degraded_after_s()) o.degraded_after_ns = Nanoseconds(c.degraded_after_s());
  if (c.has_lost_after_s()) o.lost_after_ns = Nanoseconds(c.lost_after_s());
  if (c.has_initial_lost_after_s()) o.initial_lost_after_ns = Nanoseconds(c.initial_lost_after_s());
  if (c.has_lost_sigma_m()) o.lost_sigma_m = c.lost_sigma_m();
  if (c.has_relocalization_radius_m()) o.relocalization_radius_m = c.relocalization_radius_m();
  if (c.has_relocalization_growth()) o.relocalization_growth = c.relocalization_growth();
  if (c.has_relocalization_max_radius_m()) o.relocalization_max_radius_m = c.relocalization_max_radius_m();
  if (c.has_relocalization_min_score()) o.relocalization_min_score = c.relocalization_min_score();
  if (c.has_relocalization_confirmations()) o.relocalization_confirmations = c.relocalization_confirmations();
  if (c.has_relocalization_max_peak_ratio()) o.relocalization_max_peak_ratio = c.relocalization_max_peak_ratio();
  o.max_grid_points = std::max(o.max_grid_points, o.max_scan_points);
  if (Status valid = ValidateOptions(o); !valid.ok()) return valid.error();
  return o;
}

Result<LocalizerOptions> LoadLocalizerOptions(const std::filesystem::path& path) {
  LocalizerConfig config;
  if (Status status = hal::config::LoadTextProto(path, config); !status.ok()) return status.error();
  Result<LocalizerOptions> options = LocalizerOptionsFrom(config);
  if (!options.ok()) return MakeError(path.string() + ": " + options.error().message);
  return options;
}

}  // namespace flat2d::localization
