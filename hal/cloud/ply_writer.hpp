// Writing point clouds as PLY (binary_little_endian 1.0): vertex x y z and, when given,
// nx ny nz, the format ReadPly and every mesh viewer (MeshLab, CloudCompare) read.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

// `normals` empty or one per point. An error names the file if it cannot be written.
Status WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3f>& points,
                const std::vector<Eigen::Vector3f>& normals);

// A PLY written as its points arrive, for clouds too large to gather in memory (a map made
// of many local maps): the header's vertex count is a fixed-width field, zero-padded (PLY
// readers parse it as a decimal number), patched in by Close.
class PlyStreamWriter {
 public:
  static Result<PlyStreamWriter> Open(const std::filesystem::path& path, bool with_normals);

  // `normals` one per point with normals, else empty; `pose` applied to both.
  Status Append(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                const Eigen::Matrix4f& pose = Eigen::Matrix4f::Identity());
  // Writes the count and closes the file; a writer not closed leaves a file with count 0.
  Status Close();

  std::size_t points() const { return count_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  PlyStreamWriter(std::filesystem::path path, std::unique_ptr<std::FILE, FileCloser> file, bool with_normals,
                  long count_offset);

  std::filesystem::path path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  bool with_normals_ = false;
  long count_offset_ = 0;  // where the count's digits start
  std::size_t count_ = 0;
};

}  // namespace flat2d::hal::cloud
