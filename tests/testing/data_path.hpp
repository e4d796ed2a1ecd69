// Locating the shared real-data folder from tests and benchmarks.
//
// The folder is ../shared/data beside the repository, or $FLAT2D_DATA. A test that
// needs a file calls FLAT2D_REQUIRE_DATA, which skips the test with a message naming
// the missing file, so a plain clone without the data still passes.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <gtest/gtest.h>

namespace flat2d::testing {

// The data root ($FLAT2D_DATA, else the configured default).
std::filesystem::path DataRoot();

// DataRoot()/relative if it exists.
std::optional<std::filesystem::path> FindData(const std::string& relative);

}  // namespace flat2d::testing

// Declares `variable` as the path of data file `relative`, or skips the test.
#define FLAT2D_REQUIRE_DATA(variable, relative)                                         \
  const auto variable##_found = ::flat2d::testing::FindData((relative));                  \
  if (!variable##_found) {                                                              \
    GTEST_SKIP() << "real data not found: " << (::flat2d::testing::DataRoot() / (relative)) \
                 << " (set FLAT2D_DATA to the shared data folder)";                     \
  }                                                                                     \
  const std::filesystem::path variable = *variable##_found
