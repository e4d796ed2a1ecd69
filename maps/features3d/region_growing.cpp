#include "maps/features3d/region_growing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flat2d::maps::features3d {
namespace {

constexpr std::size_t kDropped = std::numeric_limits<std::size_t>::max();

// The pixel offset of (row, col), the column wrapped round the azimuth (|col| < 2 cols).
std::size_t WrappedOffset(int row, int col, int cols) {
  if (col < 0) col += cols;
  if (col >= cols) col -= cols;
  return static_cast<std::size_t>(row) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(col);
}

}  // namespace

const Clusters& RegionGrowing::Segment(const range3d::IndexImage& image, const range3d::SurfelCloud& cloud,
                                       const Eigen::Vector3f& up) {
  const std::size_t pixels = static_cast<std::size_t>(image.rows()) * static_cast<std::size_t>(image.cols());
  ground_x_ = up.unitOrthogonal();
  ground_y_ = up.cross(ground_x_);
  piece_of_.assign(pixels, -1);
  pool_.reserve(pixels);
  piece_points_.clear();
  piece_points_.reserve(pixels);
  pieces_.clear();
  pieces_.reserve(pixels);  // at most a piece per pixel: no allocation after the first call
  parent_.reserve(pixels);
  cursor_.reserve(pixels);
  for (std::size_t offset = 0; offset < pixels; ++offset) {
    const std::int32_t index = image.indices()[offset];
    if (index < 0 || piece_of_[offset] >= 0 || !cloud.has_normal(static_cast<std::size_t>(index))) continue;
    Grow(offset, image, cloud);
  }
  parent_.resize(pieces_.size());
  for (std::size_t k = 0; k < pieces_.size(); ++k) parent_[k] = static_cast<std::int32_t>(k);
  if (options_.pole_max_width_m() > 0.0) JoinThinPieces(image, cloud);
  CollectClusters();
  return clusters_;
}

void RegionGrowing::Grow(std::size_t start, const range3d::IndexImage& image, const range3d::SurfelCloud& cloud) {
  const int rows = image.rows(), cols = image.cols();
  const int reach = static_cast<int>(options_.neighbour_cols());
  const std::int32_t* indices = image.indices().data();
  const auto piece = static_cast<std::int32_t>(pieces_.size());
  Piece& p = pieces_.emplace_back();
  p.begin = piece_points_.size();
  p.top = rows;
  p.bottom = -1;
  p.ground_min.setConstant(std::numeric_limits<float>::infinity());
  p.ground_max.setConstant(-std::numeric_limits<float>::infinity());
  pool_.clear();
  pool_.push_back(start);
  piece_of_[start] = piece;
  for (std::size_t head = 0; head < pool_.size(); ++head) {  // the pool is a FIFO over pool_
    const std::size_t offset = pool_[head];
    const auto seed = static_cast<std::size_t>(indices[offset]);
    piece_points_.push_back(static_cast<std::int32_t>(seed));
    const int row = static_cast<int>(offset / static_cast<std::size_t>(cols));
    const int col = static_cast<int>(offset % static_cast<std::size_t>(cols));
    p.top = std::min(p.top, row);
    p.bottom = std::max(p.bottom, row);
    const Eigen::Vector2f ground(cloud.points[seed].dot(ground_x_), cloud.points[seed].dot(ground_y_));
    p.ground_min = p.ground_min.cwiseMin(ground);
    p.ground_max = p.ground_max.cwiseMax(ground);
    const Seed s = SeedAt(cloud, seed);
    for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1); ++r) {
      for (int dc = -reach; dc <= reach; ++dc) {
        const std::size_t neighbour = WrappedOffset(r, col + dc, cols);
        const std::int32_t index = indices[neighbour];
        if (index < 0 || piece_of_[neighbour] >= 0 || !Joins(s, cloud, static_cast<std::size_t>(index))) continue;
        piece_of_[neighbour] = piece;
        pool_.push_back(neighbour);
      }
    }
  }
  p.size = pool_.size();
  p.joined = p.size;
}

// Every pair of touching pixels of different pieces is looked at once: each pixel's
// neighbours to its right on its row and those on the next row.
void RegionGrowing::JoinThinPieces(const range3d::IndexImage& image, const range3d::SurfelCloud& cloud) {
  const int rows = image.rows(), cols = image.cols();
  const int reach = static_cast<int>(options_.neighbour_cols());
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const std::size_t offset = WrappedOffset(row, col, cols);
      if (piece_of_[offset] < 0) continue;
      for (int r = row; r <= std::min(rows - 1, row + 1); ++r) {
        for (int dc = r == row ? 1 : -reach; dc <= reach; ++dc) JoinIfThin(offset, WrappedOffset(r, col + dc, cols), image, cloud);
      }
    }
  }
}

void RegionGrowing::JoinIfThin(std::size_t offset, std::size_t neighbour, const range3d::IndexImage& image,
                               const range3d::SurfelCloud& cloud) {
  if (piece_of_[neighbour] < 0 || piece_of_[neighbour] == piece_of_[offset]) return;  // most neighbours
  const std::size_t min_piece = options_.pole_min_piece_points();
  if (pieces_[static_cast<std::size_t>(piece_of_[offset])].size < min_piece ||
      pieces_[static_cast<std::size_t>(piece_of_[neighbour])].size < min_piece) {
    return;
  }
  const std::int32_t a = Root(piece_of_[offset]), b = Root(piece_of_[neighbour]);
  if (a == b) return;
  Piece& pa = pieces_[static_cast<std::size_t>(a)];
  const Piece& pb = pieces_[static_cast<std::size_t>(b)];
  const Eigen::Vector2f low = pa.ground_min.cwiseMin(pb.ground_min), high = pa.ground_max.cwiseMax(pb.ground_max);
  if ((high - low).norm() > static_cast<float>(options_.pole_max_width_m())) return;
  const Seed s = SeedAt(cloud, static_cast<std::size_t>(image.indices()[offset]));
  const Eigen::Vector3f& q = cloud.points[static_cast<std::size_t>(image.indices()[neighbour])];
  const float join_distance = std::min(static_cast<float>(options_.pole_join_distance_m()), std::sqrt(s.max_distance_squared));
  if (!((s.point - q).squaredNorm() < join_distance * join_distance)) return;  // and Eq. 8.2 still holds
  pa.joined += pb.joined;
  pa.top = std::min(pa.top, pb.top);
  pa.bottom = std::max(pa.bottom, pb.bottom);
  pa.ground_min = low;
  pa.ground_max = high;
  parent_[static_cast<std::size_t>(b)] = a;
}

std::int32_t RegionGrowing::Root(std::int32_t piece) {
  while (parent_[static_cast<std::size_t>(piece)] != piece) {
    const std::int32_t up = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(piece)])];
    parent_[static_cast<std::size_t>(piece)] = up;  // path halving
    piece = up;
  }
  return piece;
}

void RegionGrowing::CollectClusters() {
  clusters_.points.clear();
  clusters_.begin.assign(1, 0);
  cursor_.assign(pieces_.size(), kDropped);
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    if (parent_[k] != static_cast<std::int32_t>(k)) continue;
    const Piece& root = pieces_[k];
    if (!Kept(root)) continue;  // dropped: too few points or rows
    cursor_[k] = clusters_.begin.back();
    clusters_.begin.push_back(clusters_.begin.back() + root.joined);
  }
  clusters_.points.resize(clusters_.begin.back());
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    const auto root = static_cast<std::size_t>(Root(static_cast<std::int32_t>(k)));
    if (cursor_[root] == kDropped) continue;
    const Piece& piece = pieces_[k];
    std::copy_n(piece_points_.begin() + static_cast<std::ptrdiff_t>(piece.begin), piece.size,
                clusters_.points.begin() + static_cast<std::ptrdiff_t>(cursor_[root]));
    cursor_[root] += piece.size;
  }
}

bool RegionGrowing::Kept(const Piece& root) const {
  return root.joined > options_.min_cluster_points() && root.bottom - root.top + 1 >= static_cast<int>(options_.min_rows());
}

RegionGrowing::Seed RegionGrowing::SeedAt(const range3d::SurfelCloud& cloud, std::size_t seed) const {
  const Eigen::Vector3f& p = cloud.points[seed];
  const auto max_distance =
      static_cast<float>(options_.max_distance_m() + options_.max_distance_per_m() * static_cast<double>(p.norm()));
  const Eigen::Vector3f direction = cloud.has_line_direction(seed) ? cloud.line_directions[seed] : Eigen::Vector3f::Zero();
  return {p, cloud.normals[seed], direction, max_distance * max_distance};
}

bool RegionGrowing::Joins(const Seed& seed, const range3d::SurfelCloud& cloud, std::size_t candidate) const {
  if (!cloud.has_normal(candidate)) return false;
  const bool near = (seed.point - cloud.points[candidate]).squaredNorm() < seed.max_distance_squared;  // Eq. 8.2
  // Eq. 8.3; between two points of a line (a thin pole) their directions stand for the
  // normals, which may turn about it.
  const bool both_lines = seed.line_direction.squaredNorm() > 0.5F && cloud.has_line_direction(candidate);
  const bool aligned = both_lines ? std::abs(seed.line_direction.dot(cloud.line_directions[candidate])) > min_normal_dot_
                                  : seed.normal.dot(cloud.normals[candidate]) > min_normal_dot_;
  return either_ ? (near || aligned) : (near && aligned);
}

}  // namespace flat2d::maps::features3d
