#include "localization/localizer/localizer_options.hpp"

namespace flat2d::localization {

Status ValidateOptions(const LocalizerOptions& options) {
  if (Status window = ValidateOptions(options.map_window); !window.ok()) return window;
  if (Status graph = graph::ValidateOptions(options.graph); !graph.ok()) return MakeError("graph: " + graph.error().message);
  if (!(options.point_range_m > 0.0)) return MakeError("point_range_m must be positive");
  if (!(options.decimation_m > 0.0)) return MakeError("decimation_m must be positive");
  if (options.max_scan_points < 20 || options.max_grid_points < options.max_scan_points) {
    return MakeError("max_scan_points must be >= 20 and max_grid_points >= max_scan_points");
  }
  if (!(options.tracking_window.linear > 0.0) || !(options.tracking_window.angular > 0.0)) {
    return MakeError("tracking_window must be positive");
  }
  if (!(options.min_match_sigma_m > 0.0) || !(options.min_match_sigma_rad > 0.0)) {
    return MakeError("min_match_sigma_m and min_match_sigma_rad must be positive");
  }
  if (!(options.odometry_sigma_per_m >= 0.0) || !(options.odometry_sigma_rad_per_m >= 0.0)) {
    return MakeError("odometry_sigma_per_m and odometry_sigma_rad_per_m must be >= 0");
  }
  if (options.solve_iterations < 1) return MakeError("solve_iterations must be >= 1");
  if (options.relocalization_confirmations < 0) return MakeError("relocalization_confirmations must be >= 0");
  if (options.degraded_after_ns <= 0 || options.lost_after_ns < options.degraded_after_ns ||
      options.initial_lost_after_ns <= 0) {
    return MakeError("need 0 < degraded_after <= lost_after and initial_lost_after > 0");
  }
  if (options.max_tracking_window_m < options.tracking_window.linear ||
      options.max_tracking_window_m > options.relocalization_max_radius_m) {
    return MakeError("max_tracking_window_m must be in [tracking_window, relocalization_max_radius_m]");
  }
  if (!(options.relocalization_max_peak_ratio > 0.0 && options.relocalization_max_peak_ratio <= 1.0)) {
    return MakeError("relocalization_max_peak_ratio must be in (0, 1]");
  }
  if (!(options.relocalization_radius_m > 0.0) || options.relocalization_max_radius_m < options.relocalization_radius_m ||
      !(options.relocalization_growth >= 1.0)) {
    return MakeError("relocalization radius must be positive, growth >= 1, maximum >= the start");
  }
  return Status::Ok();
}

}  // namespace flat2d::localization
