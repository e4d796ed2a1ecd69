// The compact voxel column of thesis 7.1.2: per XY cell a float z-min and a 64-bit band
// mask, bit k set when a return fell in [z_min + k h, z_min + (k + 1) h) for band height h.
//
// Steps of AddHeight: (1) an empty column takes the return as its z-min and sets bit 0;
// (2) a return below z-min lowers z-min by whole bands, s = ceil((z_min - z) / h), and
// shifts the mask left by s, so earlier returns keep their band alignment and bands pushed
// past bit 63 fall off (Fig. 7.1, right); (3) any other return sets bit floor((z - z_min) / h)
// when that is below 64 and is dropped otherwise. Verticality is the popcount of the mask;
// a height band relative to the local ground (e.g. "obstacles at vehicle height") is a
// bitwise AND with BandMask.
#pragma once

#include <bit>
#include <cstdint>
#include <limits>

namespace flat2d::maps {

inline constexpr int kVoxelBands = 64;

struct VoxelColumn {
  float z_min = std::numeric_limits<float>::infinity();  // infinity = nothing observed
  std::uint64_t bands = 0;

  bool empty() const { return bands == 0; }
  int popcount() const { return std::popcount(bands); }
};

// Adds a return at height z (finite; the caller drops NaN returns) for band height h > 0.
void AddHeight(VoxelColumn& column, float z, float band_height_m);

// The bands covering heights [low_m, high_m) above a column's z-min (low_m < high_m,
// both >= 0), as a mask for `column.bands & mask`; bands above bit 63 are left out.
std::uint64_t BandMask(float low_m, float high_m, float band_height_m);

}  // namespace flat2d::maps
