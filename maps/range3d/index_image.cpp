#include "maps/range3d/index_image.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace flat2d::maps::range3d {

namespace {

// Points are projected a block at a time: first every point's pixel offset and depth, in
// loops with no early exit that the compiler can vectorize, then the depth test in order.
constexpr std::size_t kBlock = RangeProjection::kMaxBatch;

struct BlockPixels {
  std::array<std::int32_t, kBlock> offset;  // -1: not projected
  std::array<float, kBlock> depth;
};

// The pinhole case of RangeProjection::Project with the same arithmetic: floor(a) lands
// in [0, n) exactly when a does, and truncation is floor there. Tests combine with `&`,
// not `&&`, so that the loop has no branch.
template <bool kWithNormals>
void ProjectPinholeBlock(const PinholeIntrinsics& k, const Eigen::Vector3f* points, const Eigen::Vector3f* normals,
                         std::size_t count, const Eigen::Isometry3f& camera_T_points, BlockPixels& out) {
  // Structure of arrays first: the compute loop then runs 4 points per SSE instruction.
  std::array<std::array<float, kBlock>, 3> p, n;
  for (std::size_t i = 0; i < count; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      p[static_cast<std::size_t>(axis)][i] = points[i][axis];
      if constexpr (kWithNormals) n[static_cast<std::size_t>(axis)][i] = normals[i][axis];
    }
  }
  const Eigen::Matrix3f r = camera_T_points.linear();
  const Eigen::Vector3f t = camera_T_points.translation();
  const auto cols = static_cast<float>(k.cols), rows = static_cast<float>(k.rows);
  for (std::size_t i = 0; i < count; ++i) {
    const float px = p[0][i], py = p[1][i], pz = p[2][i];
    const float x = r(0, 0) * px + r(0, 1) * py + r(0, 2) * pz + t.x();
    const float y = r(1, 0) * px + r(1, 1) * py + r(1, 2) * pz + t.y();
    const float z = r(2, 0) * px + r(2, 1) * py + r(2, 2) * pz + t.z();
    bool valid = z > 0.0F;
    if constexpr (kWithNormals) {
      const float nx = n[0][i], ny = n[1][i], nz = n[2][i];
      const float facing = (r(0, 0) * nx + r(0, 1) * ny + r(0, 2) * nz) * x +
                           (r(1, 0) * nx + r(1, 1) * ny + r(1, 2) * nz) * y +
                           (r(2, 0) * nx + r(2, 1) * ny + r(2, 2) * nz) * z;
      valid = valid & (nx * nx + ny * ny + nz * nz >= 0.5F) & !(facing > 0.0F);  // facing away: no
    }
    const float inverse_z = 1.0F / z;
    const float u = k.fx * x * inverse_z + k.cx + 0.5F;
    const float v = k.fy * y * inverse_z + k.cy + 0.5F;
    valid = valid & (u >= 0.0F) & (u < cols) & (v >= 0.0F) & (v < rows);
    out.offset[i] = valid ? static_cast<std::int32_t>(v) * k.cols + static_cast<std::int32_t>(u) : -1;
    out.depth[i] = z;
  }
}

void ProjectBlock(const RangeProjection& projection, const Eigen::Vector3f* points, const Eigen::Vector3f* normals,
                  std::size_t count, const Eigen::Isometry3f& camera_T_points, BlockPixels& out) {
  if (projection.pinhole()) {
    if (normals != nullptr) {
      ProjectPinholeBlock<true>(projection.intrinsics(), points, normals, count, camera_T_points, out);
    } else {
      ProjectPinholeBlock<false>(projection.intrinsics(), points, normals, count, camera_T_points, out);
    }
    return;
  }
  // Structure of arrays in the camera frame, then the batch projection.
  std::array<std::array<float, kBlock>, 3> p;
  const Eigen::Matrix3f r = camera_T_points.linear();
  const Eigen::Vector3f t = camera_T_points.translation();
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3f q = r * points[i] + t;
    for (std::size_t axis = 0; axis < 3; ++axis) p[axis][i] = q[static_cast<Eigen::Index>(axis)];
  }
  projection.ProjectSpherical(p[0].data(), p[1].data(), p[2].data(), count, out.offset.data(), out.depth.data());
  if (normals == nullptr) return;
  for (std::size_t i = 0; i < count; ++i) {
    if (out.offset[i] < 0) continue;
    const Eigen::Vector3f q(p[0][i], p[1][i], p[2][i]);
    // No normal, or facing away from the viewpoint: not seen.
    if (normals[i].squaredNorm() < 0.5F || (r * normals[i]).dot(q) > 0.0F) out.offset[i] = -1;
  }
}

}  // namespace

void IndexImage::Reserve(int rows, int cols) {
  rows_ = rows;
  cols_ = cols;
  const auto pixels = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  index_.resize(pixels);
  depth_.resize(pixels);
}

void IndexImage::Clear(int rows, int cols) {
  Reserve(rows, cols);
  std::fill(index_.begin(), index_.end(), -1);
  std::fill(depth_.begin(), depth_.end(), std::numeric_limits<float>::infinity());
}

void IndexImage::Build(const RangeProjection& projection, const std::vector<Eigen::Vector3f>& points,
                       const std::vector<Eigen::Vector3f>& normals, const Eigen::Isometry3f& camera_T_points) {
  if (rows_ != projection.rows() || cols_ != projection.cols()) Reserve(projection.rows(), projection.cols());
  std::fill(index_.begin(), index_.end(), -1);
  std::fill(depth_.begin(), depth_.end(), std::numeric_limits<float>::infinity());
  const Eigen::Vector3f* with_normals = normals.empty() ? nullptr : normals.data();
  BlockPixels block;
  for (std::size_t begin = 0; begin < points.size(); begin += kBlock) {
    const std::size_t count = std::min(kBlock, points.size() - begin);
    ProjectBlock(projection, points.data() + begin, with_normals ? with_normals + begin : nullptr, count,
                 camera_T_points, block);
    for (std::size_t i = 0; i < count; ++i) {
      if (block.offset[i] < 0) continue;
      const auto offset = static_cast<std::size_t>(block.offset[i]);
      if (block.depth[i] < depth_[offset]) {  // the nearest wins; ties keep the first
        depth_[offset] = block.depth[i];
        index_[offset] = static_cast<std::int32_t>(begin + i);
      }
    }
  }
}

}  // namespace flat2d::maps::range3d
