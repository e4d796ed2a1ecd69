// Reading PCL's PCD point cloud files (PCD v0.7, and the 0.6/.7 headers older PCL wrote).
//
// Steps: parse the header lines up to DATA (VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH,
// HEIGHT, VIEWPOINT, POINTS), place the channels the PointCloud keeps (x y z: F4 or F8,
// required; intensity: any numeric type, to float; ring: any integer type, to uint16),
// then decode DATA ascii (one line per point), binary (row-major records, host = little
// endian order) or binary_compressed (LZF, lzf.hpp, of the column-major fields after two
// uint32 sizes: compressed, uncompressed). Fields the cloud does not keep are skipped by
// their SIZE * COUNT. HEIGHT > 1 is an organized cloud: the grid is the identity, -1
// where a point is NaN.
//
// Malformed input is an error naming the file and the header line or field: a SIZE with
// 3 entries for 4 FIELDS, a missing x, data shorter than POINTS records, POINTS other
// than WIDTH * HEIGHT. The one leniency is PCL's own: WIDTH 0 and HEIGHT 0 (which some
// writers leave, e.g. tier4's Nebula test clouds) or no WIDTH/HEIGHT lines mean an
// unorganized cloud of POINTS points.
#pragma once

#include <filesystem>
#include <string_view>

#include "hal/cloud/point_cloud.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

Result<PointCloud> ReadPcd(const std::filesystem::path& path);
// The same for bytes in memory; `source_name` starts error messages.
Result<PointCloud> ParsePcd(std::string_view bytes, std::string_view source_name);

}  // namespace flat2d::hal::cloud
