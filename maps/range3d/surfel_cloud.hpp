// A point cloud augmented with its local surface (thesis 5.1.1, 4.2): per point the
// normal, the curvature sigma and the information matrices NICP weighs its errors with.
//
// The arrays are parallel and sized once per cloud; a point whose neighbourhood was too
// small or not seen has `normal` zero and is skipped by correspondence search
// ("a normal is undefined", 5.1.2).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/StdVector>

namespace flat2d::maps::range3d {

struct SurfelCloud {
  std::vector<Eigen::Vector3f> points;     // sensor frame, metres
  std::vector<Eigen::Vector3f> normals;    // unit, towards the viewpoint; zero = undefined
  std::vector<float> curvature;            // sigma = l1 / (l1 + l2 + l3), Eq. 5.1
  std::vector<Eigen::Matrix3f> point_information;   // Omega^s (Eq. 5.2 inverted where flat)
  std::vector<Eigen::Matrix3f> normal_information;  // Omega^n (Eq. 5.14)

  std::size_t size() const { return points.size(); }
  bool has_normal(std::size_t i) const { return normals[i].squaredNorm() > 0.5F; }

  void Resize(std::size_t n) {
    points.resize(n);
    normals.assign(n, Eigen::Vector3f::Zero());
    curvature.assign(n, 1.0F);
    point_information.assign(n, Eigen::Matrix3f::Identity());
    normal_information.assign(n, Eigen::Matrix3f::Zero());
  }
};

}  // namespace flat2d::maps::range3d
