#include "hal/cloud/lzf.hpp"

#include <algorithm>

namespace flat2d::hal::cloud {

std::optional<std::size_t> LzfDecompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
  std::size_t ip = 0;
  std::size_t op = 0;
  while (ip < in.size()) {
    const std::size_t control = in[ip++];
    if (control < 32) {  // literal run
      const std::size_t length = control + 1;
      if (length > in.size() - ip || length > out.size() - op) return std::nullopt;
      std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(ip), length, out.begin() + static_cast<std::ptrdiff_t>(op));
      ip += length;
      op += length;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (ip == in.size()) return std::nullopt;
      length += in[ip++];
    }
    if (ip == in.size()) return std::nullopt;
    const std::size_t back = ((control & 0x1f) << 8 | in[ip++]) + 1;
    length += 2;
    if (back > op || length > out.size() - op) return std::nullopt;
    // Byte by byte: the source may overlap what this copy writes (runs).
    for (std::size_t i = 0; i < length; ++i, ++op) out[op] = out[op - back];
  }
  return op;
}

}  // namespace flat2d::hal::cloud
