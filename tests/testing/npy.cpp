#include "tests/testing/npy.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>

namespace flat2d::testing {
namespace {

bool Fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
  return false;
}

// Parses "(1200, 3)" or "(4974,)" from the header dictionary.
bool ParseShape(const std::string& header, std::vector<std::size_t>& shape) {
  const auto open = header.find("'shape': (");
  if (open == std::string::npos) return false;
  std::size_t at = open + 10;
  while (at < header.size() && header[at] != ')') {
    if (header[at] >= '0' && header[at] <= '9') {
      std::size_t end = at;
      while (end < header.size() && header[end] >= '0' && header[end] <= '9') ++end;
      shape.push_back(std::stoul(header.substr(at, end - at)));
      at = end;
    } else {
      ++at;
    }
  }
  return !shape.empty() && shape.size() <= 2;
}

}  // namespace

std::optional<NpyArray> ReadNpyFloat64(const std::filesystem::path& path, std::string* error) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  std::string bytes(file ? static_cast<std::size_t>(file.tellg()) : 0, '\0');
  file.seekg(0);
  file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) {
    Fail(error, path.string() + ": not an .npy file");
    return std::nullopt;
  }
  const std::size_t header_length = static_cast<std::uint8_t>(bytes[8]) |
                                    (static_cast<std::size_t>(static_cast<std::uint8_t>(bytes[9])) << 8);
  const std::string header = bytes.substr(10, header_length);
  NpyArray array;
  if (header.find("'descr': '<f8'") == std::string::npos || !ParseShape(header, array.shape)) {
    Fail(error, path.string() + ": expected a 1-D or 2-D '<f8' array, header " + header);
    return std::nullopt;
  }
  const std::size_t count = array.rows() * array.cols();
  if (bytes.size() < 10 + header_length + count * sizeof(double)) {
    Fail(error, path.string() + ": shorter than its header says");
    return std::nullopt;
  }
  std::vector<double> raw(count);
  std::memcpy(raw.data(), bytes.data() + 10 + header_length, count * sizeof(double));
  if (header.find("'fortran_order': True") == std::string::npos) {
    array.values = std::move(raw);
  } else {  // column-major on disk
    array.values.resize(count);
    for (std::size_t r = 0; r < array.rows(); ++r) {
      for (std::size_t c = 0; c < array.cols(); ++c) array.values[r * array.cols() + c] = raw[c * array.rows() + r];
    }
  }
  return array;
}

}  // namespace flat2d::testing
