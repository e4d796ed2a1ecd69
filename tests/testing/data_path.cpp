#include "tests/testing/data_path.hpp"

#include <cstdlib>

namespace flat2d::testing {

std::filesystem::path DataRoot() {
  if (const char* env = std::getenv("FLAT2D_DATA"); env != nullptr && *env != '\0') {
    return env;
  }
  return FLAT2D_DEFAULT_DATA_DIR;
}

std::optional<std::filesystem::path> FindData(const std::string& relative) {
  std::filesystem::path path = DataRoot() / relative;
  std::error_code error;
  if (std::filesystem::exists(path, error)) return path;
  return std::nullopt;
}

}  // namespace flat2d::testing
