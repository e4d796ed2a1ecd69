// Range-image projections pi and pi^-1 (thesis 3.1.1, Eq. 3.11): where a 3D point lands
// in a sensor's image and back.
//
// Two models. Pinhole for depth cameras: (u, v, d) = (fx x/z + cx, fy y/z + cy, z).
// Spherical for spinning LiDARs: the column is the azimuth (2 pi / cols per column, 0 at
// the -x axis, counter-clockwise seen from above), the row the laser, found by elevation
// in a table of row elevations (row 0 the highest), and the depth is the range. A
// Velodyne's rows come from its laser table; KITTI's HDL-64E, whose per-laser table the
// archive lacks, is binned by elevation into equal rows.
//
// Project() is the inner loop of projective registration, so it is inline and returns an
// invalid pixel (row < 0) instead of throwing or allocating.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace flat2d::maps::range3d {

struct PinholeIntrinsics {
  int cols = 640;
  int rows = 480;
  float fx = 525.0F;
  float fy = 525.0F;
  float cx = 319.5F;
  float cy = 239.5F;
};

// Rows of a spinning LiDAR: one elevation per row, descending (row 0 highest).
struct SphericalLayout {
  int cols = 2048;
  std::vector<float> row_elevation_rad;
  // Per row, columns added to the azimuth's column before it is cut to a pixel (empty: none).
  // A sensor's lasers fire one after another as it turns, so one firing sequence spans a
  // fraction of a column and a column border can split it; shifting each laser back by its
  // firing delay puts the whole sequence in one column (range_frame.hpp, LidarProjection).
  std::vector<float> row_column_shift;
};

struct Pixel {
  int row = -1;
  int col = -1;
  float depth = 0.0F;
  bool valid() const { return row >= 0; }
};

class RangeProjection {
 public:
  static RangeProjection Pinhole(const PinholeIntrinsics& intrinsics);
  // Fails (returns a projection with no rows) only on an empty or unsorted table.
  static RangeProjection Spherical(const SphericalLayout& layout);
  // `rows` equal elevation bins from max_elevation (row 0) down to min_elevation.
  static RangeProjection SphericalBinned(int cols, int rows, float min_elevation_rad,
                                         float max_elevation_rad);

  // A spherical projection's coarser level (a registration pyramid's, 6.3.1): the same
  // rows, cols / scale columns, so that full column c lands in column c / scale. Returns a
  // projection with no rows for a pinhole, or where scale < 1 or does not divide cols.
  RangeProjection ColumnsDividedBy(int scale) const;

  bool pinhole() const { return pinhole_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  const PinholeIntrinsics& intrinsics() const { return intrinsics_; }

  Pixel Project(const Eigen::Vector3f& p) const {
    return pinhole_ ? ProjectPinhole(p) : ProjectSpherical(p);
  }
  // Spherical Project of `count` points given as coordinate arrays, the same pixels as
  // Project one at a time: offset[i] = row * cols + col, or -1 where invalid; depth[i] the
  // range. The arithmetic runs in a loop without branches that the compiler vectorizes;
  // only the elevation table look-up is scalar. count <= kMaxBatch.
  static constexpr std::size_t kMaxBatch = 256;
  void ProjectSpherical(const float* x, const float* y, const float* z, std::size_t count, std::int32_t* offset,
                        float* depth) const;
  // pi^-1: the point seen at the centre of pixel (row, col) at `depth`.
  Eigen::Vector3f Unproject(int row, int col, float depth) const;

  // Pixels per metre of surface seen at `depth`, along columns and rows: sizes the
  // neighbourhood rectangle of a sphere of radius R (thesis 5.1.1).
  Eigen::Vector2f PixelsPerMetre(float depth) const;

 private:
  Pixel ProjectPinhole(const Eigen::Vector3f& p) const {
    if (!(p.z() > 0.0F)) return {};
    const float inverse_z = 1.0F / p.z();
    const int col = static_cast<int>(std::floor(intrinsics_.fx * p.x() * inverse_z + intrinsics_.cx + 0.5F));
    const int row = static_cast<int>(std::floor(intrinsics_.fy * p.y() * inverse_z + intrinsics_.cy + 0.5F));
    if (col < 0 || col >= cols_ || row < 0 || row >= rows_) return {};
    return {row, col, p.z()};
  }

  Pixel ProjectSpherical(const Eigen::Vector3f& p) const {
    const float range_xy_squared = p.x() * p.x() + p.y() * p.y();
    const float range = std::sqrt(range_xy_squared + p.z() * p.z());
    if (!(range > 0.0F)) return {};
    const float elevation = FastAtan2(p.z(), std::sqrt(range_xy_squared));
    const int bin = static_cast<int>(std::floor((elevation - lut_min_elevation_) * lut_bins_per_rad_));
    if (bin < 0 || bin >= static_cast<int>(elevation_lut_.size())) return {};
    const int row = elevation_lut_[static_cast<std::size_t>(bin)];
    if (row < 0) return {};
    const float shifted = (FastAtan2(p.y(), p.x()) + kPi) * cols_per_rad_ + row_column_shift_[static_cast<std::size_t>(row)];
    return {row, WrappedColumn(static_cast<int>(std::floor(shifted))), range};
  }

  // A column one turn off (a shift or the azimuth at +pi) back into [0, cols).
  int WrappedColumn(int col) const {
    if (col >= cols_) return col - cols_;
    if (col < 0) return col + cols_;
    return col;
  }

  static constexpr float kPi = 3.14159265358979F;

  // atan2 within 2e-6 rad (a degree-11 odd minimax polynomial of atan on [0, 1], folded
  // into the octants): a thousandth of a LiDAR column (2.9e-3 rad), at a fifth of libm's
  // cost, which was a quarter of a revolution's feature extraction. Only points within
  // 2e-6 rad of a pixel border can land in the neighbouring pixel.
  // Written without branches (selects only; 0/0 gives a NaN that the last select drops)
  // so that batch loops over it vectorize.
  static float FastAtan2(float y, float x) {
    const float ax = std::abs(x), ay = std::abs(y);
    const float big = std::max(ax, ay);
    const float a = std::min(ax, ay) / big, s = a * a;
    float r = a * (0.99997726F + s * (-0.33262347F + s * (0.19354346F + s * (-0.11643287F + s * (0.05265332F + s * -0.01172120F)))));
    // Each alternative computed before its select: with trapping maths (GCC's default) the
    // compiler may not hoist a conditional subtraction itself.
    const float complement = 1.57079637F - r;
    r = ay > ax ? complement : r;
    const float supplement = kPi - r;
    r = x < 0.0F ? supplement : r;
    const float negated = -r;
    r = y < 0.0F ? negated : r;
    return big > 0.0F ? r : 0.0F;
  }

  bool pinhole_ = true;
  int rows_ = 0;
  int cols_ = 0;
  PinholeIntrinsics intrinsics_;
  // Spherical: row of each fine elevation bin (-1 between or beyond the rows).
  std::vector<float> row_elevation_;
  std::vector<std::int16_t> elevation_lut_;
  std::vector<float> row_column_shift_;  // one per row, zeros where the layout has none
  float lut_min_elevation_ = 0.0F;
  float lut_bins_per_rad_ = 0.0F;
  float cols_per_rad_ = 0.0F;
  float mean_row_spacing_rad_ = 0.0F;
};

}  // namespace flat2d::maps::range3d
