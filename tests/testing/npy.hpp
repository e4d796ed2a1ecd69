// Reads NumPy .npy arrays of little-endian float64 (the format of the comma2k19 logs in
// shared/data), for tests that compare our results with a reference stored that way.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace flat2d::testing {

struct NpyArray {
  std::vector<std::size_t> shape;  // e.g. {1200, 3}
  std::vector<double> values;      // row-major whatever the file's order
  std::size_t rows() const { return shape.empty() ? 0 : shape[0]; }
  std::size_t cols() const { return shape.size() < 2 ? 1 : shape[1]; }
  double at(std::size_t row, std::size_t col = 0) const { return values[row * cols() + col]; }
};

// nullopt (with `error` set) when the file is missing, not '<f8', or not 1-D/2-D.
std::optional<NpyArray> ReadNpyFloat64(const std::filesystem::path& path, std::string* error = nullptr);

}  // namespace flat2d::testing
