#include "maps/render/top_down.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace flat2d::maps {
namespace {

// Pixel geometry derived once from the options: the sensor is pixel (centre, centre).
struct Grid {
  int centre = 0;  // also the half side in pixels
  int side = 0;
};

Error BadOption(const char* field, double value, const char* requirement) {
  return MakeError(std::string("top-down option ") + field + " = " + std::to_string(value) + ": " +
                   requirement);
}

bool PositiveFinite(double value) { return std::isfinite(value) && value > 0.0; }

Result<Grid> CheckOptions(const TopDownOptions& options) {
  if (!PositiveFinite(options.metres_per_pixel)) {
    return BadOption("metres_per_pixel", options.metres_per_pixel, "must be positive");
  }
  if (!PositiveFinite(options.half_extent_m)) {
    return BadOption("half_extent_m", options.half_extent_m, "must be positive");
  }
  const double half_px = std::round(options.half_extent_m / options.metres_per_pixel);
  if (half_px > (kMaxTopDownSidePx - 1) / 2) {
    const std::string limit = "gives an image wider than " + std::to_string(kMaxTopDownSidePx) +
                              " px at this metres_per_pixel";
    return BadOption("half_extent_m", options.half_extent_m, limit.c_str());
  }
  if (!(options.z_max_m > options.z_min_m) || !std::isfinite(options.z_max_m - options.z_min_m)) {
    return BadOption("z_max_m", options.z_max_m, "must be finite and above z_min_m");
  }
  if (!(options.intensity_max > options.intensity_min) ||
      !std::isfinite(options.intensity_max - options.intensity_min)) {
    return BadOption("intensity_max", options.intensity_max,
                     "must be finite and above intensity_min");
  }
  // Rings closer than 2 px would paint the image solid, and a tiny spacing would make
  // the ring loop practically endless.
  if (std::isnan(options.ring_spacing_m) ||
      (options.ring_spacing_m > 0.0 && options.ring_spacing_m < 2 * options.metres_per_pixel)) {
    return BadOption("ring_spacing_m", options.ring_spacing_m,
                     "must be <= 0 (no rings) or at least 2 pixels");
  }
  if (options.origin_marker_radius_px < 0) {
    return BadOption("origin_marker_radius_px", options.origin_marker_radius_px,
                     "must not be negative");
  }
  const int centre = static_cast<int>(half_px);
  return Grid{centre, 2 * centre + 1};
}

// The eight pixels symmetric to (dx, dy) about the centre.
void PlotOctants(RgbImage& image, int centre, int dx, int dy, Rgb colour) {
  for (const int sx : {-1, 1}) {
    for (const int sy : {-1, 1}) {
      image.SetClipped(centre + sx * dx, centre + sy * dy, colour);
      image.SetClipped(centre + sx * dy, centre + sy * dx, colour);
    }
  }
}

// Midpoint circle (Bresenham): integer-only, so rings are identical on every machine.
void DrawCircle(RgbImage& image, int centre, int radius, Rgb colour) {
  int x = radius;
  int y = 0;
  int decision = 1 - radius;
  while (x >= y) {
    PlotOctants(image, centre, x, y, colour);
    ++y;
    if (decision < 0) {
      decision += 2 * y + 1;
    } else {
      --x;
      decision += 2 * (y - x) + 1;
    }
  }
}

void DrawRangeRings(RgbImage& image, const Grid& grid, const TopDownOptions& options) {
  if (options.ring_spacing_m <= 0.0) return;
  // Rings up to the image corner, so the corners are not left unlabelled.
  const double corner_m = std::sqrt(2.0) * grid.centre * options.metres_per_pixel;
  for (int k = 1; k * options.ring_spacing_m <= corner_m; ++k) {
    const auto radius_px =
        static_cast<int>(std::lround(k * options.ring_spacing_m / options.metres_per_pixel));
    DrawCircle(image, grid.centre, radius_px, options.ring_colour);
  }
}

void DrawOriginMarker(RgbImage& image, const Grid& grid, const TopDownOptions& options) {
  const int r = options.origin_marker_radius_px;
  if (r == 0) return;
  for (int d = -r; d <= r; ++d) {
    image.SetClipped(grid.centre + d, grid.centre, options.origin_colour);
    image.SetClipped(grid.centre, grid.centre + d, options.origin_colour);
  }
}

Rgb ColourOf(const TopDownPoint& point, const TopDownOptions& options) {
  if (options.colour_by == TopDownColour::kIntensity) {
    return Viridis((static_cast<double>(point.intensity) - options.intensity_min) /
                   (options.intensity_max - options.intensity_min));
  }
  return Viridis((static_cast<double>(point.z) - options.z_min_m) /
                 (options.z_max_m - options.z_min_m));
}

// Projects and draws every point, keeping the highest point per pixel.
void DrawPoints(std::span<const TopDownPoint> points, const Grid& grid,
                const TopDownOptions& options, TopDownRender& render) {
  // One height per pixel; -inf means nothing drawn there yet.
  std::vector<float> top_z(
      static_cast<std::size_t>(grid.side) * static_cast<std::size_t>(grid.side),
      -std::numeric_limits<float>::infinity());
  for (const TopDownPoint& point : points) {
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) {
      ++render.non_finite;
      continue;
    }
    // Rounded in double and range-checked before the int cast, which would be UB for
    // huge coordinates.
    const double up_px = std::round(static_cast<double>(point.x) / options.metres_per_pixel);
    const double left_px = std::round(static_cast<double>(point.y) / options.metres_per_pixel);
    if (std::abs(up_px) > grid.centre || std::abs(left_px) > grid.centre) {
      ++render.outside_extent;
      continue;
    }
    ++render.drawn;
    const int row = grid.centre - static_cast<int>(up_px);
    const int col = grid.centre - static_cast<int>(left_px);
    const std::size_t index = static_cast<std::size_t>(row) * static_cast<std::size_t>(grid.side) +
                              static_cast<std::size_t>(col);
    if (!(point.z > top_z[index])) continue;  // strict: on a tie the earlier point stays
    top_z[index] = point.z;
    render.image.Set(col, row, ColourOf(point, options));
  }
}

}  // namespace

Result<TopDownRender> RenderTopDown(std::span<const TopDownPoint> points,
                                    const TopDownOptions& options) {
  const Result<Grid> grid = CheckOptions(options);
  if (!grid) return grid.error();
  TopDownRender render;
  render.image = RgbImage(grid->side, grid->side, options.background);
  DrawRangeRings(render.image, *grid, options);
  DrawPoints(points, *grid, options, render);
  DrawOriginMarker(render.image, *grid, options);
  return render;
}

}  // namespace flat2d::maps
