#include "localization/tools/shipped_config.hpp"

#include <cstdio>

namespace flat2d::localization {
namespace {

std::string FirstReadable(const char* installed, const char* source) {
  for (const char* candidate : {installed, source}) {
    if (std::FILE* f = std::fopen(candidate, "r")) {
      std::fclose(f);
      return candidate;
    }
  }
  return source;
}

}  // namespace

std::string ShippedGridConfig() { return FirstReadable(FLAT2D_INSTALLED_GRID_CONFIG, FLAT2D_SOURCE_GRID_CONFIG); }

std::string ShippedFeaturesConfig() {
  return FirstReadable(FLAT2D_INSTALLED_FEATURES_CONFIG, FLAT2D_SOURCE_FEATURES_CONFIG);
}

std::string ShippedSimOdometryConfig() {
  return FirstReadable(FLAT2D_INSTALLED_SIM_ODOMETRY_CONFIG, FLAT2D_SOURCE_SIM_ODOMETRY_CONFIG);
}

}  // namespace flat2d::localization
