#include "maps/tools/cli_args.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "hal/net/ipv4.hpp"

namespace flat2d::maps::cli {

void Fail(std::string_view tool, int status, const std::string& message) {
  std::cerr << tool << ": " << message << "\n";
  std::exit(status);
}

const char* OptionValue(std::string_view tool, int argc, char** argv, int& i) {
  if (i + 1 >= argc) Fail(tool, 1, std::string(argv[i]) + " needs a value");
  return argv[++i];
}

double ParseNumber(std::string_view tool, std::string_view flag, const char* text) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || errno != 0) {
    Fail(tool, 1, std::string(flag) + ": not a number: " + text);
  }
  return value;
}

namespace {

std::string FormatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

double ParseNumberIn(std::string_view tool, std::string_view flag, const char* text, double min, double max) {
  const double value = ParseNumber(tool, flag, text);
  if (!(value >= min && value <= max)) {
    Fail(tool, 1, std::string(flag) + ": expected a number from " + FormatNumber(min) + " to " + FormatNumber(max) +
                      ", got " + text);
  }
  return value;
}

namespace {

// The parts of "a,b,c" (an empty part where two commas meet or at an end).
std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

}  // namespace

std::vector<double> ParseNumberList(std::string_view tool, std::string_view flag, const std::string& text,
                                    std::size_t count) {
  std::vector<double> values;
  for (const std::string& part : SplitCommas(text)) values.push_back(ParseNumber(tool, flag, part.c_str()));
  if (values.size() != count) {
    Fail(tool, 1, std::string(flag) + " takes " + std::to_string(count) + " comma-separated numbers");
  }
  return values;
}

std::int64_t ParseInteger(std::string_view tool, std::string_view flag, const char* text,
                          std::int64_t min, std::int64_t max) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || errno != 0 || value < min || value > max) {
    Fail(tool, 1, std::string(flag) + ": expected an integer from " + std::to_string(min) +
                      " to " + std::to_string(max) + ", got " + text);
  }
  return value;
}

std::vector<std::int64_t> ParseIntegerList(std::string_view tool, std::string_view flag, const std::string& text,
                                           std::int64_t min, std::int64_t max) {
  std::vector<std::int64_t> values;
  for (const std::string& part : SplitCommas(text)) values.push_back(ParseInteger(tool, flag, part.c_str(), min, max));
  return values;
}

namespace {

// Levels of a coarse-to-fine schedule (pyramid scales, radii): each smaller than the one
// before, or Fail(1) naming the flag.
template <typename Value>
void RequireCoarseToFine(std::string_view tool, std::string_view flag, const std::vector<Value>& values) {
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (values[i] >= values[i - 1]) {
      Fail(tool, 1, std::string(flag) + ": the levels go coarse to fine, each smaller than the one before");
    }
  }
}

}  // namespace

std::vector<int> ParseCoarseToFine(std::string_view tool, std::string_view flag, const std::string& text, int max) {
  std::vector<int> scales;
  for (const std::int64_t scale : ParseIntegerList(tool, flag, text, 1, max)) scales.push_back(static_cast<int>(scale));
  RequireCoarseToFine(tool, flag, scales);
  return scales;
}

std::vector<double> ParseDecreasing(std::string_view tool, std::string_view flag, const std::string& text, double min,
                                    double max) {
  std::vector<double> values;
  for (const std::string& part : SplitCommas(text)) values.push_back(ParseNumberIn(tool, flag, part.c_str(), min, max));
  RequireCoarseToFine(tool, flag, values);
  return values;
}

std::uint32_t ParseAddress(std::string_view tool, std::string_view flag, const std::string& text) {
  const auto address = hal::net::ParseIpv4(text);
  if (!address) Fail(tool, 1, std::string(flag) + ": not an IPv4 address: " + text);
  return *address;
}

}  // namespace flat2d::maps::cli
