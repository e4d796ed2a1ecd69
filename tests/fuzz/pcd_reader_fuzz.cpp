// libFuzzer target: arbitrary bytes as a PCD file into ParsePcd.
//
// PCD files come from other people's tools (PCL, drivers' test dumps, converters); whatever
// the header claims and whatever the data holds, ascii, binary or LZF-compressed, parsing
// must end in a cloud or an Error without a crash, a leak, undefined behaviour or an
// allocation the input cannot account for, and a cloud must be consistent.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hal/cloud/pcd_file.hpp"
#include "tests/fuzz/cloud_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const flat2d::Result<flat2d::hal::cloud::PointCloud> cloud = flat2d::hal::cloud::ParsePcd(bytes, "fuzz.pcd");
  if (cloud.ok()) flat2d::fuzz::CheckCloud(*cloud);
  return 0;
}
