// RGB raster images and the colormap the renderers share.
//
// RgbImage is the in-memory picture every renderer draws into and WritePng saves:
// 8-bit RGB, row-major, top row first, no padding, so `pixels` is exactly what a PNG
// row sequence holds. Viridis maps a scalar in [0, 1] to colour: the table is the nine
// published viridis anchor colours (van der Walt and Smith, matplotlib 2015; the same
// anchors as R's viridisLite viridis(9)), linearly interpolated. Viridis was chosen over
// turbo because its lightness rises monotonically, so a height or intensity ramp still
// reads correctly in greyscale and to colour-blind readers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace flat2d::maps {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;

  friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3 bytes, row-major, top row first

  RgbImage() = default;
  // A width x height image filled with `fill`. Negative sizes are treated as 0.
  RgbImage(int width_px, int height_px, Rgb fill = {});

  bool Contains(int col, int row) const {
    return col >= 0 && row >= 0 && col < width && row < height;
  }
  // Unchecked access; the caller guarantees Contains(col, row).
  Rgb At(int col, int row) const;
  void Set(int col, int row, Rgb colour);
  // Set() when the pixel is inside the image, nothing otherwise: lets shapes that cross
  // the border be drawn without clipping them first.
  void SetClipped(int col, int row, Rgb colour) {
    if (Contains(col, row)) Set(col, row, colour);
  }
  void Fill(Rgb colour);

 private:
  std::size_t Offset(int col, int row) const {
    const std::size_t index = static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(col);
    return index * 3;
  }
};

// Viridis colour of t; t is clamped to [0, 1] and NaN maps to the t = 0 colour.
Rgb Viridis(double t);

// Rec. 709 luma of the gamma-encoded components, 0..255: the ordering used to check
// that a colormap gets lighter along its range.
double Luma(Rgb colour);

}  // namespace flat2d::maps
