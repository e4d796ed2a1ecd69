#include "maps/tools/cli_args.hpp"

#include <cerrno>
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

std::vector<double> ParseNumberList(std::string_view tool, std::string_view flag, const std::string& text,
                                    std::size_t count) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    values.push_back(ParseNumber(tool, flag, part.c_str()));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
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

std::uint32_t ParseAddress(std::string_view tool, std::string_view flag, const std::string& text) {
  const auto address = hal::net::ParseIpv4(text);
  if (!address) Fail(tool, 1, std::string(flag) + ": not an IPv4 address: " + text);
  return *address;
}

}  // namespace flat2d::maps::cli
