// Open3D 0.16's registrations for peer_registration.hpp: RegistrationICP with
// TransformationEstimationPointToPlane and RegistrationGeneralizedICP, with
// VoxelDownSample downsampling and EstimateNormals normals.
#pragma once

#include "localization/peers/peer_registration.hpp"

namespace flat2d::localization::peers {

// options.method is kOpen3dPointToPlane or kOpen3dGicp.
Result<PeerResult> RegisterWithOpen3d(const Points& target, const Points& source, const Eigen::Isometry3d& guess,
                                      const PeerOptions& options);

}  // namespace flat2d::localization::peers
