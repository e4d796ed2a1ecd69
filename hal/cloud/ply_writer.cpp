#include "hal/cloud/ply_writer.hpp"

#include <bit>
#include <cstdio>
#include <string>

namespace flat2d::hal::cloud {

static_assert(std::endian::native == std::endian::little, "PLY binary_little_endian is written as memory holds it");

Status WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3f>& points,
                const std::vector<Eigen::Vector3f>& normals) {
  const bool with_normals = !normals.empty();
  if (with_normals && normals.size() != points.size()) {
    return MakeError(path.string() + ": " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(points.size()) + " points");
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return MakeError(path.string() + ": cannot open for writing");
  std::fprintf(file, "ply\nformat binary_little_endian 1.0\ncomment flat2d\nelement vertex %zu\n", points.size());
  std::fprintf(file, "property float x\nproperty float y\nproperty float z\n");
  if (with_normals) std::fprintf(file, "property float nx\nproperty float ny\nproperty float nz\n");
  std::fprintf(file, "end_header\n");
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::fwrite(points[i].data(), sizeof(float), 3, file);
    if (with_normals) std::fwrite(normals[i].data(), sizeof(float), 3, file);
  }
  const bool ok = std::ferror(file) == 0;
  if (std::fclose(file) != 0 || !ok) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

}  // namespace flat2d::hal::cloud
