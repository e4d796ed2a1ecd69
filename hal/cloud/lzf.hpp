// LZF decompression (Marc Lehmann's liblzf format), which PCD's DATA binary_compressed
// uses for its column-major point data.
//
// The stream is a sequence of chunks, each opened by a control byte c: c < 32 is a run of
// c + 1 literal bytes; otherwise length L = c >> 5 (7 means one more length byte follows,
// added), then one more byte of back-reference offset, and L + 2 bytes are copied from
// ((c & 31) << 8 | next) + 1 bytes back in the output. Every read is checked against the
// input and every write and back-reference against the output, so malformed or hostile
// input ends the decode instead of reading or writing out of bounds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace flat2d::hal::cloud {

// Most output bytes one input byte can give: a back-reference of 3 bytes (control, length
// 255, offset) copies 7 + 255 + 2 = 264 bytes. Bounds the allocation for a claimed size.
inline constexpr std::size_t kLzfMaxExpansion = 88;

// Decompresses `in` into `out`; the number of bytes written, or nullopt when `in` is not
// an LZF stream whose output fits in `out`.
std::optional<std::size_t> LzfDecompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out);

}  // namespace flat2d::hal::cloud
