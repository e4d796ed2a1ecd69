// Registration of a source cloud onto a target by other libraries, the peers flat2d's NICP
// (flat2d-map register) is compared with: PCL 1.13's generalized ICP (Segal et al. 2009)
// and point-to-plane ICP, Open3D 0.16's point-to-plane ICP and generalized ICP. All start
// from the same guess with the same correspondence distance and run on one thread.
//
// Steps per method: the clouds into the library's type; optional voxel downsampling of
// both (the library's own filter); the surface statistics the method needs (point-to-plane:
// the target's normals; GICP: both clouds' covariances, which PCL estimates from the k
// nearest points and Open3D from the normals) -- together "prepare"; the library's
// registration call, timed alone (it builds its own KD-trees); then the inliers, counted
// alike for every method: registered source points whose nearest registered target point
// lies within max_distance_m at the result.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include <Eigen/Geometry>

#include "hal/common/error.hpp"
#include "localization/peers/peer_clouds.hpp"

namespace flat2d::localization::peers {

enum class PeerMethod { kPclGicp, kPclPointToPlane, kOpen3dPointToPlane, kOpen3dGicp };

inline constexpr PeerMethod kPeerMethods[] = {PeerMethod::kPclGicp, PeerMethod::kPclPointToPlane,
                                              PeerMethod::kOpen3dPointToPlane, PeerMethod::kOpen3dGicp};

struct PeerOptions {
  PeerMethod method = PeerMethod::kPclGicp;
  double max_distance_m = 0.5;   // max correspondence distance; flat2d's eps_d default
  int iterations = 30;           // outer iterations at most; Open3D's default (PCL's: 10 ICP, 200 GICP)
  double voxel_m = 0.0;          // > 0: both clouds voxel-downsampled first
  int neighbours = 20;           // k of the normals and covariances (the GICP paper's 20)
  double normal_radius_m = 0.0;  // > 0: normals from the neighbours within this radius instead
                                 // (PCL all of them, Open3D at most `neighbours`); PCL's GICP
                                 // covariances stay k-nearest, its only choice
};

struct PeerResult {
  Eigen::Isometry3d target_T_source = Eigen::Isometry3d::Identity();  // p_target = T p_source
  int iterations = -1;            // -1: the library does not report it (Open3D)
  std::optional<bool> converged;  // stopped by its criteria before the limit; nullopt: not reported (Open3D)
  int inliers = 0;
  double inlier_rmse_m = 0.0;     // of the inliers' nearest-point distances
  std::size_t source_points = 0;  // as registered, after downsampling
  std::size_t target_points = 0;
  double prepare_ms = 0.0;        // downsampling, normals, covariances
  double time_ms = 0.0;           // the registration call, wall clock
  double cpu_ms = 0.0;            // the same span in process CPU time: about time_ms on one thread
};

std::optional<PeerMethod> ParsePeerMethod(std::string_view name);
std::string_view PeerMethodName(PeerMethod method);

// `source` registered onto `target` from `guess` (target_T_source). An error carries the
// library's message when it refuses the input (e.g. too few points for its neighbourhoods).
Result<PeerResult> RegisterPeer(const Points& target, const Points& source, const Eigen::Isometry3d& guess,
                                const PeerOptions& options);

// For the backends, after downsampling: an error unless both clouds have `neighbours`
// points, the fewest their neighbourhoods need (PCL's GICP would index covariances it
// could not compute).
Status EnoughPoints(std::size_t target_points, std::size_t source_points, int neighbours);

// Confines both libraries to the calling thread and quiets Open3D's log to errors: OpenMP,
// which PCL's and Open3D's parallel loops use, to one thread. Process-wide state, so the
// tool's main and the tests call it, never the registration itself.
void UseOneThreadAndQuietLogs();

}  // namespace flat2d::localization::peers
