#include "localization/localizer/localizer_state.hpp"

namespace flat2d::localization {

std::string_view LocalizerStateName(LocalizerState state) {
  switch (state) {
    case LocalizerState::kInitializing: return "INITIALIZING";
    case LocalizerState::kLocalized: return "LOCALIZED";
    case LocalizerState::kDegraded: return "DEGRADED";
    case LocalizerState::kLost: return "LOST";
  }
  return "UNKNOWN";
}

}  // namespace flat2d::localization
