#include "localization/registration/correspondence_finder.hpp"

namespace flat2d::localization::registration {

using maps::range3d::SurfelCloud;

ProjectiveCorrespondenceFinder::ProjectiveCorrespondenceFinder(const SurfelCloud& target,
                                                               const maps::range3d::RangeProjection& projection,
                                                               const maps::range3d::IndexImage* target_image)
    : target_(target), projection_(projection), target_image_(target_image ? *target_image : own_target_image_) {
  if (target_image == nullptr) {
    own_target_image_.Build(projection, target.points, target.normals, Eigen::Isometry3f::Identity());
  }
  source_image_.Reserve(projection.rows(), projection.cols());
}

void ProjectiveCorrespondenceFinder::Find(const SurfelCloud& source, const Eigen::Isometry3f& target_T_source,
                                          const NicpOptions& options, std::vector<Correspondence>& pairs) {
  pairs.clear();
  const CompatibilityTest test(options);
  source_image_.Build(projection_, source.points, source.normals, target_T_source);
  const Eigen::Matrix3f rotation = target_T_source.linear();
  const std::vector<std::int32_t>& target_pixels = target_image_.indices();
  const std::vector<std::int32_t>& source_pixels = source_image_.indices();
  for (std::size_t pixel = 0; pixel < target_pixels.size(); ++pixel) {
    const std::int32_t i = target_pixels[pixel];
    const std::int32_t j = source_pixels[pixel];
    if (i < 0 || j < 0) continue;
    const auto si = static_cast<std::size_t>(i), sj = static_cast<std::size_t>(j);
    if (Compatible(target_, si, target_T_source * source.points[sj], rotation * source.normals[sj],
                   source.curvature[sj], test)) {
      pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
    }
  }
}

KdTreeCorrespondenceFinder::KdTreeCorrespondenceFinder(const SurfelCloud& target, float alpha)
    : target_(target), alpha_(alpha), tree_(target.points, &target.normals, alpha) {}

void KdTreeCorrespondenceFinder::Find(const SurfelCloud& source, const Eigen::Isometry3f& target_T_source,
                                      const NicpOptions& options, std::vector<Correspondence>& pairs) {
  pairs.clear();
  const CompatibilityTest test(options);
  const Eigen::Matrix3f rotation = target_T_source.linear();
  for (std::size_t j = 0; j < source.size(); ++j) {
    if (!source.has_normal(j)) continue;
    const Eigen::Vector3f point = target_T_source * source.points[j];
    const Eigen::Vector3f normal = rotation * source.normals[j];
    const float query[6] = {point.x(), point.y(), point.z(), alpha_ * normal.x(), alpha_ * normal.y(), alpha_ * normal.z()};
    const auto [i, distance_squared] = tree_.Nearest(query);
    if (i < 0) return;
    if (Compatible(target_, static_cast<std::size_t>(i), point, normal, source.curvature[j], test)) {
      pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
    }
  }
}

}  // namespace flat2d::localization::registration
