// PCL's generalized ICP and point-to-plane ICP on the peers' clouds (pcl_registration.hpp),
// with the preparation outside the timed align() call and the inliers counted afterwards.
#include "localization/peers/pcl_registration.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include <pcl/common/common.h>
#include <pcl/common/transforms.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>
#include <pcl/search/kdtree.h>

#include "localization/peers/span_timer.hpp"

namespace flat2d::localization::peers {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using NormalCloud = pcl::PointCloud<pcl::PointNormal>;

// Both methods stop when an iteration moves less than 0.1 mm and 0.1 mrad. PCL's own
// point-to-plane thresholds are 0, which no step meets: it would always run to the
// iteration limit (its rotation test compares the cos of the step angle, which floats
// resolve to about 0.5 mrad: smaller rotations pass it). GICP's own are 0.5 mm and 2 mrad
// per entry of the step's matrix, coarser than the errors measured: on the static VLP-16
// sweeps it stopped after its first step from the truth, 0.3 mm long.
constexpr double kStepTranslationM = 1e-4;
constexpr double kStepRotationRad = 1e-4;

// PCL 1.13 keeps the iteration count protected, with no getter.
template <typename Registration>
class Counted : public Registration {
 public:
  int iterations() const { return this->nr_iterations_; }
};

// GICP estimates its covariances inside align() unless given them; this computes them with
// PCL's own code beforehand, so that they count as preparation, not registration.
class Gicp : public Counted<pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> {
 public:
  MatricesVectorPtr Covariances(const Cloud::Ptr& cloud) {
    auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    tree->setInputCloud(cloud);
    auto covariances = pcl::make_shared<MatricesVector>();
    computeCovariances<pcl::PointXYZ>(cloud, tree, *covariances);
    return covariances;
  }
};

// VoxelGrid numbers voxels with 32-bit integers and, when the cloud's extent overflows
// them, warns and passes the cloud through unfiltered; this says so instead.
Result<Cloud::Ptr> Downsample(Cloud::Ptr cloud, double voxel_m) {
  if (voxel_m <= 0.0) return cloud;
  pcl::PointXYZ low, high;
  pcl::getMinMax3D(*cloud, low, high);
  double voxels = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    voxels *= std::floor(static_cast<double>(high.data[axis] - low.data[axis]) / voxel_m) + 1.0;
  }
  if (voxels > static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    char message[96];
    std::snprintf(message, sizeof message, "PCL VoxelGrid: voxels of %g m overflow its 32-bit voxel index here",
                  voxel_m);
    return MakeError(message);
  }
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(cloud);
  const auto leaf = static_cast<float>(voxel_m);
  grid.setLeafSize(leaf, leaf, leaf);
  auto filtered = pcl::make_shared<Cloud>();
  grid.filter(*filtered);
  return filtered;
}

// The target with its normals. Points without one (fewer than 3 neighbours within the
// radius) are dropped: a NaN normal would make the linear system NaN.
NormalCloud::Ptr WithNormals(const Cloud::Ptr& cloud, const PeerOptions& options) {
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(cloud);
  estimation.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  if (options.normal_radius_m > 0.0) estimation.setRadiusSearch(options.normal_radius_m);
  else estimation.setKSearch(options.neighbours);
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute(normals);
  auto out = pcl::make_shared<NormalCloud>();
  out->reserve(cloud->size());
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const pcl::Normal& n = normals[i];
    if (!std::isfinite(n.normal_x) || !std::isfinite(n.normal_y) || !std::isfinite(n.normal_z)) continue;
    const pcl::PointXYZ& p = (*cloud)[i];
    out->push_back(pcl::PointNormal(p.x, p.y, p.z, n.normal_x, n.normal_y, n.normal_z, n.curvature));
  }
  return out;
}

// The source needs no normals: point-to-plane (TransformationEstimationPointToPlaneLLS)
// reads the target's only.
NormalCloud::Ptr WithoutNormals(const Cloud::Ptr& cloud) {
  auto out = pcl::make_shared<NormalCloud>();
  out->reserve(cloud->size());
  for (const pcl::PointXYZ& p : *cloud) out->push_back(pcl::PointNormal(p.x, p.y, p.z));
  return out;
}

// Source points whose nearest target point is within max_distance_m at `target_T_source`.
template <typename Point>
void CountInliers(const pcl::PointCloud<Point>& source, const typename pcl::PointCloud<Point>::Ptr& target,
                  const Eigen::Matrix4f& target_T_source, double max_distance_m, PeerResult& result) {
  pcl::PointCloud<Point> moved;
  pcl::transformPointCloud(source, moved, target_T_source);
  pcl::KdTreeFLANN<Point> tree;
  tree.setInputCloud(target);
  pcl::Indices nearest(1);
  std::vector<float> squared(1);
  const double max_squared = max_distance_m * max_distance_m;
  double sum = 0.0;
  result.inliers = 0;
  for (const Point& p : moved) {
    if (tree.nearestKSearch(p, 1, nearest, squared) == 1 && static_cast<double>(squared[0]) <= max_squared) {
      ++result.inliers;
      sum += static_cast<double>(squared[0]);
    }
  }
  result.inlier_rmse_m = result.inliers > 0 ? std::sqrt(sum / result.inliers) : 0.0;
}

void SetTransform(const Eigen::Matrix4f& target_T_source, PeerResult& result) {
  result.target_T_source.matrix() = target_T_source.cast<double>();
}

Result<PeerResult> RegisterGicp(const Cloud::Ptr& target, const Cloud::Ptr& source, const Eigen::Isometry3d& guess,
                                const PeerOptions& options, const SpanTimer& prepare) {
  PeerResult result;
  Gicp gicp;
  gicp.setInputTarget(target);
  gicp.setInputSource(source);
  gicp.setCorrespondenceRandomness(options.neighbours);
  gicp.setTargetCovariances(gicp.Covariances(target));  // after the inputs, which reset them
  gicp.setSourceCovariances(gicp.Covariances(source));
  gicp.setMaxCorrespondenceDistance(options.max_distance_m);
  gicp.setMaximumIterations(options.iterations);
  gicp.setTransformationEpsilon(kStepTranslationM);  // GICP compares each entry, unsquared
  gicp.setRotationEpsilon(kStepRotationRad);
  result.prepare_ms = prepare.WallMs();

  Cloud aligned;
  const SpanTimer timer;
  gicp.align(aligned, guess.matrix().cast<float>());
  result.time_ms = timer.WallMs();
  result.cpu_ms = timer.CpuMs();
  result.iterations = gicp.iterations();
  // PCL's GICP raises its converged flag on reaching the iteration limit too.
  result.converged = gicp.hasConverged() && result.iterations < options.iterations;
  SetTransform(gicp.getFinalTransformation(), result);
  CountInliers(*source, target, gicp.getFinalTransformation(), options.max_distance_m, result);
  result.source_points = source->size();
  result.target_points = target->size();
  return result;
}

Result<PeerResult> RegisterPointToPlane(const Cloud::Ptr& target, const Cloud::Ptr& source,
                                        const Eigen::Isometry3d& guess, const PeerOptions& options,
                                        const SpanTimer& prepare) {
  using Criteria = pcl::registration::DefaultConvergenceCriteria<float>;
  PeerResult result;
  const NormalCloud::Ptr target_normals = WithNormals(target, options);
  const NormalCloud::Ptr source_points = WithoutNormals(source);
  if (Status enough = EnoughPoints(target_normals->size(), source_points->size(), 3); !enough.ok()) {
    return enough.error();
  }
  Counted<pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal>> icp;
  icp.setInputTarget(target_normals);
  icp.setInputSource(source_points);
  icp.setMaxCorrespondenceDistance(options.max_distance_m);
  icp.setMaximumIterations(options.iterations);
  icp.setTransformationEpsilon(kStepTranslationM * kStepTranslationM);  // compared with the squared step
  icp.setTransformationRotationEpsilon(std::cos(kStepRotationRad));
  result.prepare_ms = prepare.WallMs();

  NormalCloud aligned;
  const SpanTimer timer;
  icp.align(aligned, guess.matrix().cast<float>());
  result.time_ms = timer.WallMs();
  result.cpu_ms = timer.CpuMs();
  result.iterations = icp.iterations();
  const auto state = icp.getConvergeCriteria()->getConvergenceState();
  result.converged = state == Criteria::CONVERGENCE_CRITERIA_TRANSFORM ||
                     state == Criteria::CONVERGENCE_CRITERIA_ABS_MSE || state == Criteria::CONVERGENCE_CRITERIA_REL_MSE;
  SetTransform(icp.getFinalTransformation(), result);
  CountInliers(*source_points, target_normals, icp.getFinalTransformation(), options.max_distance_m, result);
  result.source_points = source_points->size();
  result.target_points = target_normals->size();
  return result;
}

}  // namespace

Result<PeerResult> RegisterWithPcl(const Points& target, const Points& source, const Eigen::Isometry3d& guess,
                                   const PeerOptions& options) {
  try {
    const SpanTimer prepare;
    auto target_cloud = Downsample(ToPcl(target), options.voxel_m);
    if (!target_cloud.ok()) return target_cloud.error();
    auto source_cloud = Downsample(ToPcl(source), options.voxel_m);
    if (!source_cloud.ok()) return source_cloud.error();
    if (Status enough = EnoughPoints((*target_cloud)->size(), (*source_cloud)->size(), options.neighbours);
        !enough.ok()) {
      return enough.error();
    }
    if (options.method == PeerMethod::kPclGicp) {
      return RegisterGicp(*target_cloud, *source_cloud, guess, options, prepare);
    }
    return RegisterPointToPlane(*target_cloud, *source_cloud, guess, options, prepare);
  } catch (const std::exception& e) {
    return MakeError(std::string("PCL: ") + e.what());
  }
}

}  // namespace flat2d::localization::peers
