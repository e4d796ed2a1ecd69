#include "hal/cloud/ply_writer.hpp"

#include <bit>
#include <string>

namespace flat2d::hal::cloud {
namespace {

static_assert(std::endian::native == std::endian::little, "PLY binary_little_endian is written as memory holds it");

constexpr int kCountDigits = 20;  // any std::size_t

}  // namespace

Result<PlyStreamWriter> PlyStreamWriter::Open(const std::filesystem::path& path, bool with_normals) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (file == nullptr) return MakeError(path.string() + ": cannot open for writing");
  std::fprintf(file.get(), "ply\nformat binary_little_endian 1.0\ncomment flat2d\nelement vertex ");
  const long count_offset = std::ftell(file.get());
  std::fprintf(file.get(), "%0*d\n", kCountDigits, 0);
  std::fprintf(file.get(), "property float x\nproperty float y\nproperty float z\n");
  if (with_normals) std::fprintf(file.get(), "property float nx\nproperty float ny\nproperty float nz\n");
  std::fprintf(file.get(), "end_header\n");
  if (std::ferror(file.get()) != 0) return MakeError(path.string() + ": write failed");
  return PlyStreamWriter(path, std::move(file), with_normals, count_offset);
}

PlyStreamWriter::PlyStreamWriter(std::filesystem::path path, std::unique_ptr<std::FILE, FileCloser> file,
                                 bool with_normals, long count_offset)
    : path_(std::move(path)), file_(std::move(file)), with_normals_(with_normals), count_offset_(count_offset) {}

Status PlyStreamWriter::Append(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                               const Eigen::Matrix4f& pose) {
  if (file_ == nullptr) return MakeError(path_.string() + ": already closed");
  if ((with_normals_ ? points.size() : 0) != normals.size()) {
    return MakeError(path_.string() + ": " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(points.size()) + " points" + (with_normals_ ? "" : " (opened without normals)"));
  }
  const Eigen::Matrix3f rotation = pose.topLeftCorner<3, 3>();
  const Eigen::Vector3f translation = pose.topRightCorner<3, 1>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f point = rotation * points[i] + translation;
    std::fwrite(point.data(), sizeof(float), 3, file_.get());
    if (!with_normals_) continue;
    const Eigen::Vector3f normal = rotation * normals[i];
    std::fwrite(normal.data(), sizeof(float), 3, file_.get());
  }
  count_ += points.size();
  if (std::ferror(file_.get()) != 0) return MakeError(path_.string() + ": write failed");
  return Status::Ok();
}

Status PlyStreamWriter::Close() {
  if (file_ == nullptr) return MakeError(path_.string() + ": already closed");
  const bool patched = std::fseek(file_.get(), count_offset_, SEEK_SET) == 0 &&
                       std::fprintf(file_.get(), "%0*zu", kCountDigits, count_) == kCountDigits;
  const bool ok = patched && std::ferror(file_.get()) == 0;
  if (std::fclose(file_.release()) != 0 || !ok) return MakeError(path_.string() + ": write failed");
  return Status::Ok();
}

Status WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3f>& points,
                const std::vector<Eigen::Vector3f>& normals) {
  if (!normals.empty() && normals.size() != points.size()) {
    return MakeError(path.string() + ": " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(points.size()) + " points");
  }
  auto writer = PlyStreamWriter::Open(path, !normals.empty());
  if (!writer.ok()) return writer.error();
  if (Status s = writer->Append(points, normals); !s.ok()) return s;
  return writer->Close();
}

}  // namespace flat2d::hal::cloud
