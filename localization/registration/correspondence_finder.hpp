// Correspondence search of NICP against a fixed target cloud, two ways:
//
//  - projective (thesis 5.1.2): the target's index image is built once (Eq. 5.4); each
//    iteration projects the moved source into the same image (Eq. 5.5) with a depth buffer,
//    and a pixel holding a point of each is a candidate pair. For organized sensor data.
//  - KD-tree (Eq. 6.10): the nearest target point in (p, alpha n) to each moved source
//    point. For unorganized clouds.
//
// Candidates pass through Compatible() (Eq. 5.6-5.8). Buffers are sized once per target.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "localization/registration/correspondence.hpp"
#include "maps/range3d/index_image.hpp"
#include "maps/range3d/point_kdtree.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::localization::registration {

class CorrespondenceFinder {
 public:
  virtual ~CorrespondenceFinder() = default;
  // The pairs between the target and source moved by target_T_source; `pairs` is reused.
  virtual void Find(const maps::range3d::SurfelCloud& source, const Eigen::Isometry3f& target_T_source,
                    const NicpOptions& options, std::vector<Correspondence>& pairs) = 0;
};

class ProjectiveCorrespondenceFinder final : public CorrespondenceFinder {
 public:
  // `target`, `projection` and `target_image` must outlive the finder. A null
  // `target_image` is built here from the target's points; a frame's own measurement
  // image (its points where the sensor saw them) saves that projection.
  ProjectiveCorrespondenceFinder(const maps::range3d::SurfelCloud& target,
                                 const maps::range3d::RangeProjection& projection,
                                 const maps::range3d::IndexImage* target_image = nullptr);
  void Find(const maps::range3d::SurfelCloud& source, const Eigen::Isometry3f& target_T_source,
            const NicpOptions& options, std::vector<Correspondence>& pairs) override;

 private:
  const maps::range3d::SurfelCloud& target_;
  const maps::range3d::RangeProjection& projection_;
  maps::range3d::IndexImage own_target_image_;
  const maps::range3d::IndexImage& target_image_;
  maps::range3d::IndexImage source_image_;
};

class KdTreeCorrespondenceFinder final : public CorrespondenceFinder {
 public:
  // `target` must outlive the finder; alpha weighs normals against positions (Eq. 6.10).
  KdTreeCorrespondenceFinder(const maps::range3d::SurfelCloud& target, float alpha);
  void Find(const maps::range3d::SurfelCloud& source, const Eigen::Isometry3f& target_T_source,
            const NicpOptions& options, std::vector<Correspondence>& pairs) override;

 private:
  const maps::range3d::SurfelCloud& target_;
  float alpha_;
  maps::range3d::PointKdTree<6> tree_;
};

}  // namespace flat2d::localization::registration
