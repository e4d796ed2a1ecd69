#include "maps/render/image.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace flat2d::maps {
namespace {

// Viridis at t = 0, 1/8, ..., 1 (sRGB). Nine anchors keep the piecewise-linear curve
// within a couple of levels of the full 256-entry table while still rising in luma on
// every segment (checked in image_test).
constexpr std::array<Rgb, 9> kViridisAnchors = {{
    {0x44, 0x01, 0x54},
    {0x47, 0x2d, 0x7b},
    {0x3b, 0x52, 0x8b},
    {0x2c, 0x72, 0x8e},
    {0x21, 0x90, 0x8c},
    {0x27, 0xad, 0x81},
    {0x5d, 0xc8, 0x63},
    {0xaa, 0xdc, 0x32},
    {0xfd, 0xe7, 0x25},
}};

std::uint8_t Lerp(std::uint8_t a, std::uint8_t b, double f) {
  const double v = static_cast<double>(a) + (static_cast<double>(b) - a) * f;
  return static_cast<std::uint8_t>(std::lround(v));
}

}  // namespace

RgbImage::RgbImage(int width_px, int height_px, Rgb fill)
    : width(std::max(width_px, 0)), height(std::max(height_px, 0)) {
  pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  Fill(fill);
}

Rgb RgbImage::At(int col, int row) const {
  assert(Contains(col, row));
  const std::size_t i = Offset(col, row);
  return {pixels[i], pixels[i + 1], pixels[i + 2]};
}

void RgbImage::Set(int col, int row, Rgb colour) {
  assert(Contains(col, row));
  const std::size_t i = Offset(col, row);
  pixels[i] = colour.r;
  pixels[i + 1] = colour.g;
  pixels[i + 2] = colour.b;
}

void RgbImage::Fill(Rgb colour) {
  for (std::size_t i = 0; i + 2 < pixels.size(); i += 3) {
    pixels[i] = colour.r;
    pixels[i + 1] = colour.g;
    pixels[i + 2] = colour.b;
  }
}

Rgb Viridis(double t) {
  // !(t > 0) also catches NaN, which would otherwise poison the index arithmetic.
  if (!(t > 0.0)) return kViridisAnchors.front();
  if (t >= 1.0) return kViridisAnchors.back();
  const double scaled = t * static_cast<double>(kViridisAnchors.size() - 1);
  const auto lower = static_cast<std::size_t>(scaled);  // < size - 1 because t < 1
  const double f = scaled - static_cast<double>(lower);
  const Rgb& a = kViridisAnchors[lower];
  const Rgb& b = kViridisAnchors[lower + 1];
  return {Lerp(a.r, b.r, f), Lerp(a.g, b.g, f), Lerp(a.b, b.b, f)};
}

double Luma(Rgb colour) { return 0.2126 * colour.r + 0.7152 * colour.g + 0.0722 * colour.b; }

}  // namespace flat2d::maps
