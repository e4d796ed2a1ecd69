// Top-down (bird's-eye) picture of one LiDAR point set, for eyeballing scans and maps.
//
// The image is square and centred on the sensor, x forward pointing up the image and
// y left pointing left, so the picture reads like a map with the vehicle heading up.
// Steps: check the options; fill the background; draw range rings every
// ring_spacing_m around the sensor in a faint grey; project each point to the nearest
// pixel (points outside the square, or with non-finite coordinates, are counted and
// skipped); where several points land on one pixel keep the highest, because that is
// the one seen from above (ties keep the earlier point, so the output depends only on
// the input); colour it by height or intensity through Viridis; draw the sensor origin
// marker last so points never hide it. The sensor sits exactly on the centre pixel:
// the side is 2 * round(half_extent_m / metres_per_pixel) + 1 pixels.
#pragma once

#include <cstddef>
#include <span>

#include "hal/common/error.hpp"
#include "maps/render/image.hpp"

namespace flat2d::maps {

// One return in the sensor frame (x forward, y left, z up; metres).
struct TopDownPoint {
  float x = 0;
  float y = 0;
  float z = 0;
  float intensity = 0;  // 0..255 as the sensor reports it
};

enum class TopDownColour {
  kHeight,     // z from z_min_m (dark) to z_max_m (light)
  kIntensity,  // intensity from intensity_min (dark) to intensity_max (light)
};

struct TopDownOptions {
  double metres_per_pixel = 0.1;  // > 0
  double half_extent_m = 50.0;    // > 0; the image covers [-half, +half] in x and y
  TopDownColour colour_by = TopDownColour::kHeight;
  double z_min_m = -3.0;  // heights at or below map to the first colour
  double z_max_m = 5.0;   // heights at or above map to the last colour; > z_min_m
  double intensity_min = 0.0;
  double intensity_max = 255.0;  // > intensity_min
  Rgb background{0, 0, 0};
  double ring_spacing_m = 10.0;  // <= 0 draws no rings; else at least 2 pixels
  Rgb ring_colour{48, 48, 48};   // faint on the black background, under the points
  Rgb origin_colour{255, 255, 255};
  int origin_marker_radius_px = 3;  // arms of the cross at the sensor; 0 draws none
};

// Largest image side RenderTopDown accepts. It bounds memory (RGB plus a float height
// per pixel: ~117 MB at 4097 px) and still covers +-200 m, beyond any Velodyne's range,
// at the default 0.1 m per pixel.
inline constexpr int kMaxTopDownSidePx = 4097;

struct TopDownRender {
  RgbImage image;
  std::size_t drawn = 0;           // points that landed on a pixel (including hidden ones)
  std::size_t outside_extent = 0;  // finite points whose nearest pixel is off the image
  std::size_t non_finite = 0;      // points with a NaN or infinite x, y or z
};

// Renders `points`. Fails only on invalid options (the error names the field).
Result<TopDownRender> RenderTopDown(std::span<const TopDownPoint> points,
                                    const TopDownOptions& options = {});

}  // namespace flat2d::maps
