// libFuzzer target: arbitrary bytes as a PLY file into ParsePly.
//
// PLY files come from scanners' archives and mesh tools; whatever the header's element
// counts, list counts and grid shape claim, ASCII or binary of either byte order, parsing
// must end in a cloud or an Error without a crash, a leak, undefined behaviour or an
// allocation the input cannot account for, and a cloud's range grid must only name
// vertices it has.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hal/cloud/ply_file.hpp"
#include "tests/fuzz/cloud_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const flat2d::Result<flat2d::hal::cloud::PointCloud> cloud = flat2d::hal::cloud::ParsePly(bytes, "fuzz.ply");
  if (cloud.ok()) flat2d::fuzz::CheckCloud(*cloud);
  return 0;
}
