#include "hal/cloud/scalar.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

namespace flat2d::hal::cloud {
namespace {

template <typename T>
T Load(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

// Each branch converts its own type: a ?: over int32_t and uint32_t would convert the
// signed value to unsigned first.
double LoadInteger(const unsigned char* b, ScalarType type) {
  const bool is_signed = type.kind == ScalarKind::kSigned;
  switch (type.size) {
    case 1:
      if (is_signed) return static_cast<double>(Load<std::int8_t>(b));
      return static_cast<double>(Load<std::uint8_t>(b));
    case 2:
      if (is_signed) return static_cast<double>(Load<std::int16_t>(b));
      return static_cast<double>(Load<std::uint16_t>(b));
    case 4:
      if (is_signed) return static_cast<double>(Load<std::int32_t>(b));
      return static_cast<double>(Load<std::uint32_t>(b));
    default:
      if (is_signed) return static_cast<double>(Load<std::int64_t>(b));
      return static_cast<double>(Load<std::uint64_t>(b));
  }
}

}  // namespace

bool IsDecodable(ScalarType type) {
  if (type.kind == ScalarKind::kFloat) return type.size == 4 || type.size == 8;
  return type.size == 1 || type.size == 2 || type.size == 4 || type.size == 8;
}

double LoadScalar(const char* bytes, ScalarType type, bool big_endian) {
  unsigned char b[8];
  std::memcpy(b, bytes, static_cast<std::size_t>(type.size));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + type.size);
  if (type.integer()) return LoadInteger(b, type);
  return type.size == 4 ? static_cast<double>(Load<float>(b)) : Load<double>(b);
}

Result<std::string> ReadFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return MakeError(path.string() + ": cannot open");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad() || bytes.bad()) return MakeError(path.string() + ": cannot read");
  return std::move(bytes).str();
}

std::vector<std::string_view> SplitWords(std::string_view line) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

bool ParseNumber(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);  // from_chars refuses '+'
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return !token.empty() && error == std::errc() && end == token.data() + token.size();
}

bool ParseCount(std::string_view token, std::uint64_t& value) {
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return !token.empty() && error == std::errc() && end == token.data() + token.size();
}

std::string FormatNumber(double value) {
  if (IsIntegerIn(value, -1e15, 1e15)) return std::to_string(static_cast<std::int64_t>(value));
  return std::to_string(value);
}

bool IsIntegerIn(double value, double low, double high) {
  return value >= low && value <= high && std::floor(value) == value;
}

}  // namespace flat2d::hal::cloud
