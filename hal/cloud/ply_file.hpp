// Reading PLY point files: vertices, and the range grid of Stanford range scans.
//
// Steps: parse the header (ply_header.hpp); then read the elements in file order, from
// ASCII text (whitespace-separated values) or binary of either byte order. Of element
// vertex the cloud keeps x, y, z (required, any scalar type, to float), intensity
// (optional) and nx, ny, nz (optional, all three or none); other properties, faces and
// other elements are read past, list properties by their counts. Element range_grid (the Stanford 3D Scanning Repository's scans: obj_info
// num_cols 512 / num_rows 400, "property list uchar int vertex_indices") fills the grid:
// one cell per list, row-major in file order (in the Stanford scans row 0 is the scan's
// lowest y), holding its vertex or -1 for an empty list.
//
// Errors name the source and where: the header line, or the data line (ASCII) or byte
// (binary) with the element, its index and the property: data that ends early, a grid
// without obj_info num_cols/num_rows or with another cell count, a cell listing more than
// one vertex, a vertex index out of range.
#pragma once

#include <filesystem>
#include <string_view>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

Result<PointCloud> ReadPly(const std::filesystem::path& path);
// The same for bytes in memory; `source_name` starts error messages.
Result<PointCloud> ParsePly(std::string_view bytes, std::string_view source_name);

}  // namespace flat2d::hal::cloud
