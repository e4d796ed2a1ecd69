// The header of a PLY file (Turk's polygon file format, as the Stanford 3D Scanning
// Repository and most mesh tools write it): the format, the elements in file order with
// their properties, and the obj_info lines of Stanford range scans.
//
// Steps: "ply", then "format ascii|binary_little_endian|binary_big_endian 1.0", then
// comment / obj_info / element / property lines up to end_header. Property types are any
// of PLY's names, old (char uchar short ushort int uint float double) and sized (int8 ...
// float64); a list property has an integer count type and an item type. Errors name the
// source, the header line and the element or property: "x.ply: header line 5 (property
// x): unknown type 'flaot'".
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/cloud/scalar.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

struct PlyProperty {
  std::string name;
  ScalarType type;          // the value's type, or a list's item type
  bool list = false;
  ScalarType count_type;    // lists: the type of the item count before the items
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;  // at most kMaxPlyElements
  std::vector<PlyProperty> properties;
  std::size_t line = 0;     // header line of "element"
};

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  // Stanford range scans: the range_grid is num_cols x num_rows cells.
  std::optional<std::uint64_t> num_cols, num_rows;
  std::size_t data_offset = 0;  // first byte after the end_header line
  std::size_t data_line = 0;    // line number of end_header (1-based)
};

// Vertex and grid indices are int32.
inline constexpr std::uint64_t kMaxPlyElements = 0x7fffffff;

Result<PlyHeader> ParsePlyHeader(std::string_view bytes, std::string_view source_name);

}  // namespace flat2d::hal::cloud
