// The header of a PCD file (PCL's point cloud format, v0.5-0.7): the lines up to and
// including DATA, checked against each other, with each field's place in a record.
//
// Steps: split each line into a keyword and its entries ('#' lines are comments); check
// every per-field line (SIZE, TYPE, COUNT) has one entry per FIELDS entry; combine TYPE
// and SIZE into a scalar type; settle WIDTH x HEIGHT = POINTS with PCL's rules for old
// headers (no WIDTH/HEIGHT, or both 0: unorganized, WIDTH = POINTS, HEIGHT = 1). Errors
// name the source and the header line: "x.pcd: header line 3 (SIZE): 3 entries for 4 FIELDS".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hal/cloud/scalar.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

struct PcdField {
  std::string name;
  ScalarType type;
  int count = 1;            // values per point
  std::size_t offset = 0;   // bytes before this field in a row-major record

  std::size_t bytes() const { return static_cast<std::size_t>(type.size) * static_cast<std::size_t>(count); }
};

enum class PcdData { kAscii, kBinary, kBinaryCompressed };

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t record_bytes = 0;  // one point, all fields
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  std::uint64_t points = 0;      // = width * height, at most kMaxPcdPoints
  PcdData data = PcdData::kAscii;
  std::size_t data_offset = 0;   // first byte after the DATA line
  std::size_t data_line = 0;     // line number of the DATA line (1-based)
};

// Grid cells index points as int32.
inline constexpr std::uint64_t kMaxPcdPoints = 0x7fffffff;

Result<PcdHeader> ParsePcdHeader(std::string_view bytes, std::string_view source_name);

}  // namespace flat2d::hal::cloud
