// A point cloud augmented with its local surface (thesis 5.1.1, 4.2): per point the
// normal, the curvature sigma and the information NICP weighs its errors with.
//
// Both information matrices of Eq. 5.13 have one shape: the identity where the surface is
// curved, and the disc of Eq. 5.2 / 5.14 where it is flat, 1/eps along the normal and 1
// across, i.e. Omega = I + g n n^T with g = 1/eps - 1 (flat) or 0 (curved). Storing g
// instead of two 3x3 matrices keeps a point at 32 bytes and lets the linear system sum
// the identity and rank-one parts in closed form (linear_system.cpp).
//
// The arrays are parallel and sized once per cloud; a point whose neighbourhood was too
// small or not seen has `normal` zero and is skipped by correspondence search
// ("a normal is undefined", 5.1.2).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace flat2d::maps::range3d {

struct SurfelCloud {
  std::vector<Eigen::Vector3f> points;   // sensor frame, metres
  std::vector<Eigen::Vector3f> normals;  // unit, towards the viewpoint; zero = undefined
  std::vector<float> curvature;          // sigma = l1 / (l1 + l2 + l3), Eq. 5.1
  std::vector<float> disc_gain;          // g of Omega = I + g n n^T
  // Only where SurfaceStatisticsOptions::line_max_middle_share asks for them (3D features),
  // else empty: per point the unit direction of a neighbourhood that is a line (a thin
  // pole), whose normal is only defined up to a turn about that line; zero elsewhere.
  std::vector<Eigen::Vector3f> line_directions;

  std::size_t size() const { return points.size(); }
  bool has_normal(std::size_t i) const { return normals[i].squaredNorm() > 0.5F; }
  bool has_line_direction(std::size_t i) const {
    return !line_directions.empty() && line_directions[i].squaredNorm() > 0.5F;
  }

  // Omega^s = Omega^n of point i (Eq. 5.2 inverted, 5.14), for diagnostics and tests.
  Eigen::Matrix3f Information(std::size_t i) const {
    return Eigen::Matrix3f::Identity() + disc_gain[i] * normals[i] * normals[i].transpose();
  }

  void Resize(std::size_t n) {
    points.resize(n);
    normals.assign(n, Eigen::Vector3f::Zero());
    curvature.assign(n, 1.0F);
    disc_gain.assign(n, 0.0F);
  }
};

}  // namespace flat2d::maps::range3d
