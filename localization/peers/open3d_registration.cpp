// Open3D's point-to-plane ICP and generalized ICP on the peers' clouds
// (open3d_registration.hpp), with the preparation outside the timed registration call and
// the inliers evaluated afterwards.
#include "localization/peers/open3d_registration.hpp"

#include <exception>
#include <string>

#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/pipelines/registration/GeneralizedICP.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include "localization/peers/span_timer.hpp"

namespace flat2d::localization::peers {
namespace {

namespace registration = open3d::pipelines::registration;
using open3d::geometry::PointCloud;

std::shared_ptr<PointCloud> Downsample(std::shared_ptr<PointCloud> cloud, double voxel_m) {
  return voxel_m > 0.0 ? cloud->VoxelDownSample(voxel_m) : cloud;
}

void EstimateNormals(PointCloud& cloud, const PeerOptions& options) {
  if (options.normal_radius_m > 0.0) {
    cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(options.normal_radius_m, options.neighbours));
  } else {
    cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(options.neighbours));
  }
}

registration::RegistrationResult Register(const PointCloud& target, const PointCloud& source,
                                          const Eigen::Isometry3d& guess, const PeerOptions& options) {
  registration::ICPConvergenceCriteria criteria;  // relative fitness and RMSE changes of 1e-6
  criteria.max_iteration_ = options.iterations;
  if (options.method == PeerMethod::kOpen3dGicp) {
    return registration::RegistrationGeneralizedICP(source, target, options.max_distance_m, guess.matrix(),
                                                    registration::TransformationEstimationForGeneralizedICP(),
                                                    criteria);
  }
  return registration::RegistrationICP(source, target, options.max_distance_m, guess.matrix(),
                                       registration::TransformationEstimationPointToPlane(), criteria);
}

}  // namespace

Result<PeerResult> RegisterWithOpen3d(const Points& target, const Points& source, const Eigen::Isometry3d& guess,
                                      const PeerOptions& options) {
  try {
    PeerResult result;
    const SpanTimer prepare;
    const std::shared_ptr<PointCloud> target_cloud = Downsample(ToOpen3d(target), options.voxel_m);
    const std::shared_ptr<PointCloud> source_cloud = Downsample(ToOpen3d(source), options.voxel_m);
    if (Status enough = EnoughPoints(target_cloud->points_.size(), source_cloud->points_.size(), options.neighbours);
        !enough.ok()) {
      return enough.error();
    }
    EstimateNormals(*target_cloud, options);
    // GICP makes each point's covariance from its normal (the GICP paper's plane model,
    // variance epsilon along the normal), so it needs the source's too; point-to-plane
    // reads the target's only.
    if (options.method == PeerMethod::kOpen3dGicp) EstimateNormals(*source_cloud, options);
    result.prepare_ms = prepare.WallMs();

    const SpanTimer timer;
    const registration::RegistrationResult registered = Register(*target_cloud, *source_cloud, guess, options);
    result.time_ms = timer.WallMs();
    result.cpu_ms = timer.CpuMs();
    result.target_T_source.matrix() = registered.transformation_;
    // Open3D reports neither the iterations nor why it stopped (PeerResult's defaults).
    const registration::RegistrationResult evaluated =
        registration::EvaluateRegistration(*source_cloud, *target_cloud, options.max_distance_m,
                                           registered.transformation_);
    result.inliers = static_cast<int>(evaluated.correspondence_set_.size());
    result.inlier_rmse_m = evaluated.inlier_rmse_;
    result.source_points = source_cloud->points_.size();
    result.target_points = target_cloud->points_.size();
    return result;
  } catch (const std::exception& e) {
    // Open3D's LogError throws std::runtime_error.
    return MakeError(std::string("Open3D: ") + e.what());
  }
}

}  // namespace flat2d::localization::peers
