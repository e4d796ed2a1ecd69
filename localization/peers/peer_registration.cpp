// The method names, the dispatch to the PCL and Open3D backends, and the process-wide
// thread and log settings (peer_registration.hpp).
#include "localization/peers/peer_registration.hpp"

#include <omp.h>

#include <cstdlib>
#include <string>

#include <open3d/utility/Logging.h>

#include "localization/peers/open3d_registration.hpp"
#include "localization/peers/pcl_registration.hpp"

namespace flat2d::localization::peers {

std::optional<PeerMethod> ParsePeerMethod(std::string_view name) {
  for (PeerMethod method : kPeerMethods) {
    if (name == PeerMethodName(method)) return method;
  }
  return std::nullopt;
}

std::string_view PeerMethodName(PeerMethod method) {
  switch (method) {
    case PeerMethod::kPclGicp: return "pcl-gicp";
    case PeerMethod::kPclPointToPlane: return "pcl-point-to-plane";
    case PeerMethod::kOpen3dPointToPlane: return "o3d-point-to-plane";
    case PeerMethod::kOpen3dGicp: return "o3d-gicp";
  }
  return "unknown";
}

Result<PeerResult> RegisterPeer(const Points& target, const Points& source, const Eigen::Isometry3d& guess,
                                const PeerOptions& options) {
  switch (options.method) {
    case PeerMethod::kPclGicp:
    case PeerMethod::kPclPointToPlane: return RegisterWithPcl(target, source, guess, options);
    case PeerMethod::kOpen3dPointToPlane:
    case PeerMethod::kOpen3dGicp: return RegisterWithOpen3d(target, source, guess, options);
  }
  return MakeError("unknown registration method");
}

Status EnoughPoints(std::size_t target_points, std::size_t source_points, int neighbours) {
  const auto needed = static_cast<std::size_t>(neighbours);
  if (target_points >= needed && source_points >= needed) return Status::Ok();
  return MakeError("target " + std::to_string(target_points) + " and source " + std::to_string(source_points) +
                   " points to register, fewer than the " + std::to_string(neighbours) + " neighbours of a normal");
}

void UseOneThreadAndQuietLogs() {
  // Both libraries' loops are OpenMP regions entered from the calling thread, whose team
  // size this sets. Open3D 0.16 sizes some of them itself (EstimateNormals:
  // num_threads(utility::EstimateMaxThreads())), and EstimateMaxThreads asks OpenMP only
  // when OMP_NUM_THREADS or OMP_DYNAMIC is in the environment, else it takes the number
  // of physical cores; so the variable is set too (read at each call, not at start-up).
  setenv("OMP_NUM_THREADS", "1", 1);
  omp_set_dynamic(0);
  omp_set_num_threads(1);
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
}

}  // namespace flat2d::localization::peers
