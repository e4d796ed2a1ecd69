// Scalar values of point files, shared by the PCD and PLY readers.
//
// Both formats describe each channel by a kind (signed, unsigned, floating) and a size in
// bytes: PCD with its TYPE/SIZE pairs, PLY with its type names. LoadScalar decodes one
// stored value of either byte order to double, which holds every 8-32-bit integer and
// every float exactly (64-bit integers round, which no coordinate, intensity or ring
// needs). The text helpers are the ones both readers use: a whole-file read whose
// errors name the path, splitting a header line into words, and strict parsing of one
// ASCII token.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hal/common/error.hpp"

namespace flat2d::hal::cloud {

enum class ScalarKind { kSigned, kUnsigned, kFloat };

struct ScalarType {
  ScalarKind kind = ScalarKind::kFloat;
  int size = 4;  // bytes: 1, 2, 4 or 8 for integers, 4 or 8 for floats

  bool integer() const { return kind != ScalarKind::kFloat; }
};

// Whether LoadScalar can decode `type` (the sizes above).
bool IsDecodable(ScalarType type);

// The value stored at `bytes`, which must hold type.size readable bytes.
double LoadScalar(const char* bytes, ScalarType type, bool big_endian);

// The file's bytes; errors "<path>: cannot open" and "<path>: cannot read".
Result<std::string> ReadFileBytes(const std::filesystem::path& path);

// The words of `line`, split at spaces and tabs; a trailing '\r' (CRLF files) is no word.
std::vector<std::string_view> SplitWords(std::string_view line);

// `token` as a number, all of it: decimal or exponent notation, "nan", "inf". PCD writes
// "nan" where an organized cloud has no return.
bool ParseNumber(std::string_view token, double& value);

// `token` as a non-negative decimal integer, all of it.
bool ParseCount(std::string_view token, std::uint64_t& value);

// `value` for an error message: integers without decimals.
std::string FormatNumber(double value);

// Whether `value` is an integer in [low, high]: list counts, vertex indices and rings
// arrive as doubles from LoadScalar and ParseNumber.
bool IsIntegerIn(double value, double low, double high);

}  // namespace flat2d::hal::cloud
