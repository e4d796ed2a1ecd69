#include "hal/cloud/kitti_bin_file.hpp"

#include <string>

#include "hal/cloud/scalar.hpp"

namespace flat2d::hal::cloud {
namespace {

constexpr std::size_t kRecordBytes = 16;  // x, y, z, reflectance: float32 each

}  // namespace

Result<PointCloud> ParseKittiBin(std::string_view bytes, std::string_view source_name) {
  if (bytes.size() % kRecordBytes != 0) {
    return MakeError(std::string(source_name) + ": size " + std::to_string(bytes.size()) +
                     " bytes is not a multiple of 16 (x, y, z, reflectance as float32)");
  }
  const std::size_t count = bytes.size() / kRecordBytes;
  constexpr ScalarType kFloat32{ScalarKind::kFloat, 4};
  PointCloud cloud;
  cloud.points.reserve(count);
  cloud.intensity.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const char* record = bytes.data() + i * kRecordBytes;
    const auto value = [&](int k) { return static_cast<float>(LoadScalar(record + 4 * k, kFloat32, false)); };
    cloud.points.emplace_back(value(0), value(1), value(2));
    cloud.intensity.push_back(value(3));
  }
  return cloud;
}

Result<PointCloud> ReadKittiBin(const std::filesystem::path& path) {
  const Result<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.error();
  return ParseKittiBin(*bytes, path.string());
}

}  // namespace flat2d::hal::cloud
