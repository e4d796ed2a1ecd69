// PNG files for RgbImage, through libpng.
//
// Encoding and decoding both run on memory buffers; the file functions only move bytes,
// so one libpng path serves files, tests and tools, and a failed encode never leaves a
// half-written file behind. libpng reports errors by longjmp: each libpng phase runs in
// a small function that holds setjmp and nothing with a destructor, and the error
// callback copies libpng's message into a fixed buffer that becomes the Error. Steps of
// a write: check the image, encode (8-bit RGB, no interlace, no time chunk, so equal
// images give equal bytes), write the file. Steps of a read: read the file, check the
// signature, read the header, choose transforms that turn any PNG into 8-bit RGB
// (palette and grey expanded, 16-bit stripped, alpha dropped), read the rows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "hal/common/error.hpp"
#include "maps/render/image.hpp"

namespace flat2d::maps {

// Largest width or height DecodePng accepts: bounds the allocation a hostile or
// corrupt header can ask for (16384^2 RGB is 768 MiB).
inline constexpr int kMaxPngSidePx = 16384;

// PNG bytes of `image`. Fails if the image is empty or `pixels` does not hold
// width * height * 3 bytes.
Result<std::vector<std::uint8_t>> EncodePng(const RgbImage& image);

// Encodes `image` and writes it to `path` (replacing it). Errors name the path.
Status WritePng(const RgbImage& image, const std::filesystem::path& path);

// The image in PNG bytes, converted to 8-bit RGB.
Result<RgbImage> DecodePng(std::span<const std::uint8_t> bytes);

// Reads and decodes the PNG file at `path`. Errors name the path.
Result<RgbImage> ReadPng(const std::filesystem::path& path);

}  // namespace flat2d::maps
