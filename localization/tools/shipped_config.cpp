#include "localization/tools/shipped_config.hpp"

#include <cstdio>

namespace flat2d::localization {

std::string ShippedGridConfig() {
  for (const char* candidate : {FLAT2D_INSTALLED_GRID_CONFIG, FLAT2D_SOURCE_GRID_CONFIG}) {
    if (std::FILE* f = std::fopen(candidate, "r")) {
      std::fclose(f);
      return candidate;
    }
  }
  return FLAT2D_SOURCE_GRID_CONFIG;
}

}  // namespace flat2d::localization
