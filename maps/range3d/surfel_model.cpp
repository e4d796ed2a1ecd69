#include "maps/range3d/surfel_model.hpp"

#include <algorithm>

namespace flat2d::maps::range3d {

namespace {

// omega of one measurement at `depth`: isotropic noise growing with depth, in units of a
// measurement at 1 m.
float MeasurementWeight(float depth, DepthWeighting weighting) {
  const float d = std::max(depth, 1e-2F);
  return weighting == DepthWeighting::kInverse ? 1.0F / d : 1.0F / (d * d);
}

}  // namespace

SurfelModel::SurfelModel(const SurfelModelOptions& options) : options_(options) {}

void SurfelModel::Render(const RangeProjection& projection, const Eigen::Isometry3f& model_T_camera, SurfelCloud& view,
                         IndexImage& image) const {
  const Eigen::Isometry3f camera_T_model = model_T_camera.inverse();
  image.Build(projection, cloud_.points, cloud_.normals, camera_T_model);  // nearest facing point per pixel
  std::size_t visible = 0;
  for (const std::int32_t index : image.indices()) visible += index >= 0 ? 1 : 0;
  view.Resize(visible);
  const Eigen::Matrix3f rotation = camera_T_model.linear();
  std::size_t next = 0;
  for (int row = 0; row < image.rows(); ++row) {
    for (int col = 0; col < image.cols(); ++col) {
      const std::int32_t index = image.at(row, col);
      if (index < 0) continue;
      const auto i = static_cast<std::size_t>(index);
      view.points[next] = camera_T_model * cloud_.points[i];
      view.normals[next] = rotation * cloud_.normals[i];
      view.curvature[next] = cloud_.curvature[i];
      view.disc_gain[next] = cloud_.disc_gain[i];
      image.Set(row, col, static_cast<std::int32_t>(next), image.depth(row, col));
      ++next;
    }
  }
}

MergeStats SurfelModel::Merge(const SurfelCloud& frame, const IndexImage& frame_image, const RangeProjection& projection,
                              const Eigen::Isometry3f& model_T_camera) {
  MergeStats stats;
  ClusterModelPoints(frame, frame_image, projection, model_T_camera.inverse(), stats);
  Compact();
  AddFramePoints(frame, frame_image, model_T_camera, stats);
  DropOldest(stats);
  return stats;
}

void SurfelModel::ClusterModelPoints(const SurfelCloud& frame, const IndexImage& frame_image,
                                     const RangeProjection& projection, const Eigen::Isometry3f& camera_T_model,
                                     MergeStats& stats) {
  clusters_.assign(frame_image.indices().size(), Cluster{});
  remove_.assign(cloud_.size(), 0);
  const Eigen::Matrix3f rotation = camera_T_model.linear();
  for (std::size_t i = 0; i < cloud_.size(); ++i) {
    const Eigen::Vector3f point = camera_T_model * cloud_.points[i];
    const Pixel pixel = projection.Project(point);
    if (!pixel.valid()) continue;  // outside the frame's view: untouched
    const std::int32_t j = frame_image.at(pixel.row, pixel.col);
    if (j < 0 || !frame.has_normal(static_cast<std::size_t>(j))) continue;
    const float measured = frame_image.depth(pixel.row, pixel.col);
    const float tau = std::max(options_.tau_min_m, options_.tau_ratio * measured);
    if (measured - pixel.depth > tau) {  // seen through: replaced by the new measurement
      remove_[i] = 1;
      ++stats.replaced;
      continue;
    }
    if (pixel.depth - measured > tau) continue;  // behind the new surface: occluded, kept
    const Eigen::Vector3f normal = rotation * cloud_.normals[i];
    if (normal.dot(frame.normals[static_cast<std::size_t>(j)]) < options_.min_normal_dot) continue;
    Cluster& cluster = clusters_[static_cast<std::size_t>(pixel.row) * static_cast<std::size_t>(frame_image.cols()) +
                                 static_cast<std::size_t>(pixel.col)];
    const float w = weight_[i];
    cluster.point_sum += w * point;
    cluster.normal_sum += w * normal;
    cluster.curvature_sum += w * cloud_.curvature[i];
    cluster.weight += w;
    remove_[i] = 1;
    ++stats.merged;
  }
}

// Removes the points marked during clustering, keeping the others in order.
void SurfelModel::Compact() {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < cloud_.size(); ++i) {
    if (remove_[i]) continue;
    cloud_.points[kept] = cloud_.points[i];
    cloud_.normals[kept] = cloud_.normals[i];
    cloud_.curvature[kept] = cloud_.curvature[i];
    cloud_.disc_gain[kept] = cloud_.disc_gain[i];
    weight_[kept] = weight_[i];
    ++kept;
  }
  cloud_.points.resize(kept);
  cloud_.normals.resize(kept);
  cloud_.curvature.resize(kept);
  cloud_.disc_gain.resize(kept);
  weight_.resize(kept);
}

// Eq. 5.22: each frame point with its pixel's cluster, weighted by omega.
void SurfelModel::AddFramePoints(const SurfelCloud& frame, const IndexImage& frame_image,
                                 const Eigen::Isometry3f& model_T_camera, MergeStats& stats) {
  const Eigen::Matrix3f rotation = model_T_camera.linear();
  for (int row = 0; row < frame_image.rows(); ++row) {
    for (int col = 0; col < frame_image.cols(); ++col) {
      const std::int32_t index = frame_image.at(row, col);
      if (index < 0 || !frame.has_normal(static_cast<std::size_t>(index))) continue;
      const auto j = static_cast<std::size_t>(index);
      const Cluster& cluster =
          clusters_[static_cast<std::size_t>(row) * static_cast<std::size_t>(frame_image.cols()) + static_cast<std::size_t>(col)];
      const float w = MeasurementWeight(frame_image.depth(row, col), options_.weighting);
      const float total = w + cluster.weight;
      const Eigen::Vector3f point = (w * frame.points[j] + cluster.point_sum) / total;
      const Eigen::Vector3f normal = (w * frame.normals[j] + cluster.normal_sum).normalized();
      const float curvature = (w * frame.curvature[j] + cluster.curvature_sum) / total;
      Append(model_T_camera * point, rotation * normal, curvature, std::min(total, options_.max_weight));
      ++stats.added;
    }
  }
}

void SurfelModel::Append(const Eigen::Vector3f& point, const Eigen::Vector3f& normal, float curvature, float weight) {
  cloud_.points.push_back(point);
  cloud_.normals.push_back(normal);
  cloud_.curvature.push_back(curvature);
  cloud_.disc_gain.push_back(curvature < options_.flat_curvature ? 1.0F / options_.disc_epsilon - 1.0F : 0.0F);
  weight_.push_back(weight);
}

// Keeps the model within max_points by dropping the points written longest ago. Points
// are appended merge by merge and Compact() keeps their order, so those are the first.
void SurfelModel::DropOldest(MergeStats& stats) {
  if (cloud_.size() <= options_.max_points) return;
  const std::size_t excess = cloud_.size() - options_.max_points;
  remove_.assign(cloud_.size(), 0);
  std::fill(remove_.begin(), remove_.begin() + static_cast<std::ptrdiff_t>(excess), std::uint8_t{1});
  stats.dropped = excess;
  Compact();
}

}  // namespace flat2d::maps::range3d
