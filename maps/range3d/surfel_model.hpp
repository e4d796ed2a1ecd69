// A merged model of registered range frames (thesis 5.1.4, 5.2.3): the scene that frame-
// to-model tracking registers each new frame against, kept at about one point per pixel
// of the views it was seen from.
//
// Merging a frame seen from model_T_camera clusters by projection (Fig. 5.3): each model
// point is projected into the frame's image and compared with the frame's depth D^c at
// that pixel, tau apart:
//   - D^c - D^r > tau: the new beam passes through the model point: it is removed
//     (replaced by the new measurement);
//   - D^r - D^c > tau: the model point lies behind the new surface (occluded): kept;
//   - |D^r - D^c| <= tau: same surface: the point joins the pixel's cluster.
// Each frame point then becomes one model point, the information-weighted mean of itself
// and its cluster (Eq. 5.22: one scalar weight omega per point for position and normal,
// normals renormalized). Model points outside the frame's view, or where the frame has no
// normal, are untouched, so only where the frame saw is anything recomputed.
//
// Render() is the other half: the model seen from a camera pose, depth-buffered into an
// index image, as the reference cloud of projective registration (5.2.2).
//
// Values the thesis leaves open (stated in docs/benchmarks.md): tau = max(tau_min,
// tau_ratio * depth); omega of a measurement 1 / depth^2 (a depth camera's isotropic noise
// grows with depth; ch. 6's LiDAR local maps take 1 / depth, `weighting`), summed and
// capped so that the model keeps following the scene; the
// model bounded by max_points, dropping the points seen longest ago.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "maps/range3d/index_image.hpp"
#include "maps/range3d/projection.hpp"
#include "maps/range3d/surfel_cloud.hpp"

namespace flat2d::maps::range3d {

// How a measurement's weight omega falls with its depth d.
enum class DepthWeighting : std::uint8_t {
  kInverseSquare,  // 1 / d^2: a depth camera's noise (Eq. 5.22)
  kInverse,        // 1 / d: the rich points of LiDAR local maps (Eq. 6.4, merged by 6.11-6.12)
};

struct SurfelModelOptions {
  float tau_min_m = 0.01F;          // tau of 5.1.4 near the sensor
  float tau_ratio = 0.03F;          // ... and as a share of the depth beyond
  float min_normal_dot = 0.5F;      // a cluster member's normal within 60 deg of the frame's
  float max_weight = 50.0F;         // omega cap, in units of one measurement at 1 m
  std::size_t max_points = 3'000'000;  // ~100 MB: ten full 640x480 views
  float flat_curvature = 0.02F;     // disc information below this curvature (Eq. 5.2)
  float disc_epsilon = 1e-3F;
  DepthWeighting weighting = DepthWeighting::kInverseSquare;
};

struct MergeStats {
  std::size_t merged = 0;    // model points absorbed into a cluster
  std::size_t replaced = 0;  // model points seen through
  std::size_t added = 0;     // model points written (one per frame point with a normal)
  std::size_t dropped = 0;   // removed to stay within max_points
};

class SurfelModel {
 public:
  explicit SurfelModel(const SurfelModelOptions& options);

  // Merges `frame` (points in the camera frame, with normals; `frame_image` its pixels in
  // `projection`) seen from model_T_camera.
  MergeStats Merge(const SurfelCloud& frame, const IndexImage& frame_image, const RangeProjection& projection,
                   const Eigen::Isometry3f& model_T_camera);

  // The model seen from model_T_camera through `projection`: `view` holds the visible
  // points (camera frame, one per pixel, nearest first, facing the camera) and `image`
  // their pixels.
  void Render(const RangeProjection& projection, const Eigen::Isometry3f& model_T_camera, SurfelCloud& view,
              IndexImage& image) const;

  const SurfelCloud& cloud() const { return cloud_; }  // model frame
  const std::vector<float>& weights() const { return weight_; }
  std::size_t size() const { return cloud_.size(); }

 private:
  struct Cluster {
    Eigen::Vector3f point_sum = Eigen::Vector3f::Zero();   // sum omega p (camera frame)
    Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();  // sum omega n
    float curvature_sum = 0.0F;
    float weight = 0.0F;
  };

  void ClusterModelPoints(const SurfelCloud& frame, const IndexImage& frame_image, const RangeProjection& projection,
                          const Eigen::Isometry3f& camera_T_model, MergeStats& stats);
  void Compact();
  void AddFramePoints(const SurfelCloud& frame, const IndexImage& frame_image, const Eigen::Isometry3f& model_T_camera,
                      MergeStats& stats);
  void DropOldest(MergeStats& stats);
  void Append(const Eigen::Vector3f& point, const Eigen::Vector3f& normal, float curvature, float weight);

  const SurfelModelOptions options_;
  SurfelCloud cloud_;
  std::vector<float> weight_;             // omega per point; points in the order merged
  std::vector<std::uint8_t> remove_;      // per model point, set during a merge
  std::vector<Cluster> clusters_;         // per frame pixel
};

}  // namespace flat2d::maps::range3d
