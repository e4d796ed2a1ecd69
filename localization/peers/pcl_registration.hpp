// PCL 1.13's registrations for peer_registration.hpp: pcl::GeneralizedIterativeClosestPoint
// and pcl::IterativeClosestPointWithNormals (point-to-plane, linear least squares), with
// pcl::VoxelGrid downsampling and pcl::NormalEstimation normals.
#pragma once

#include "localization/peers/peer_registration.hpp"

namespace flat2d::localization::peers {

// options.method is kPclGicp or kPclPointToPlane.
Result<PeerResult> RegisterWithPcl(const Points& target, const Points& source, const Eigen::Isometry3d& guess,
                                   const PeerOptions& options);

}  // namespace flat2d::localization::peers
