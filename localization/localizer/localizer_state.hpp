// What the localizer can say about its fix (DESIGN.md "L2G factor graph", issue 9 item 3).
#pragma once

#include <cstdint>
#include <string_view>

namespace flat2d::localization {

enum class LocalizerState : std::uint8_t {
  kInitializing,  // no initial pose yet: no fix
  kLocalized,     // a scan match was accepted within degraded_after
  kDegraded,      // no accepted match for degraded_after: poses follow odometry, covariance grows
  kLost,          // no accepted match for lost_after (or too uncertain): relocalizing, widening
};

std::string_view LocalizerStateName(LocalizerState state);

}  // namespace flat2d::localization
