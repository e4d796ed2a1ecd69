// A PCD binary_compressed payload written by the reference encoder: liblzf 3.6's
// lzf_compress (Debian liblzf1) on six points in PCD's column-major layout, fields
// x y z (float32) intensity (uint8) ring (uint16). The runs of equal values make the
// encoder emit back-references, long ones included, not only literals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace flat2d::hal::cloud {

#pragma pack(push, 1)
struct GoldenColumns {
  float x[6] = {1.5f, 1.5f, 1.5f, 1.5f, -2.25f, 3.0f};
  float y[6] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  float z[6] = {-1.25f, -1.25f, -1.25f, -1.25f, -1.25f, -1.25f};
  std::uint8_t intensity[6] = {7, 7, 7, 7, 200, 255};
  std::uint16_t ring[6] = {0, 1, 2, 3, 15, 65535};
};
#pragma pack(pop)

inline constexpr std::size_t kGoldenUncompressedBytes = 90;
static_assert(sizeof(GoldenColumns) == kGoldenUncompressedBytes);

inline constexpr std::string_view kGoldenLzf{
    "\x04\x00\x00\xc0\x3f\x00\xe0\x04\x03\x08\x10\xc0\x00\x00\x40\x40\x00\x00\x00\x20\x17\xe0\x0b\x03\x01\xa0"
    "\xbf\xe0\x0b\x03\x00\x07\x20\x00\x0d\xc8\xff\x00\x00\x01\x00\x02\x00\x03\x00\x0f\x00\xff\xff",
    49};

}  // namespace flat2d::hal::cloud
