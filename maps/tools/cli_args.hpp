// Small helpers shared by the command-line tools: failing with a message and an exit
// status, and parsing option values with range checks.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace flat2d::maps::cli {

// Prints "<tool>: <message>" to stderr and exits with `status`.
[[noreturn]] void Fail(std::string_view tool, int status, const std::string& message);

// The value after option argv[i] (advancing i), or Fail(1) saying the option needs one.
const char* OptionValue(std::string_view tool, int argc, char** argv, int& i);

// The value of option `flag`, or Fail(1) naming the flag and the text.
double ParseNumber(std::string_view tool, std::string_view flag, const char* text);
// ... within [min, max], or Fail(1) naming the flag and the range.
double ParseNumberIn(std::string_view tool, std::string_view flag, const char* text, double min, double max);
std::int64_t ParseInteger(std::string_view tool, std::string_view flag, const char* text,
                          std::int64_t min, std::int64_t max);
// `count` comma-separated numbers ("1.5,-2,0.1"), or Fail(1) naming the flag.
std::vector<double> ParseNumberList(std::string_view tool, std::string_view flag, const std::string& text,
                                    std::size_t count);
// Comma-separated integers within [min, max] ("8,4,2"), or Fail(1) naming the flag.
std::vector<std::int64_t> ParseIntegerList(std::string_view tool, std::string_view flag, const std::string& text,
                                           std::int64_t min, std::int64_t max);
// A pyramid's scales ("4,2,1"): integers within [1, max], coarse to fine (each smaller
// than the one before), or Fail(1) naming the flag.
std::vector<int> ParseCoarseToFine(std::string_view tool, std::string_view flag, const std::string& text, int max);
// Comma-separated numbers within [min, max], coarse to fine (each smaller than the one
// before: "0.1,0.03"), or Fail(1) naming the flag.
std::vector<double> ParseDecreasing(std::string_view tool, std::string_view flag, const std::string& text, double min,
                                    double max);
std::uint32_t ParseAddress(std::string_view tool, std::string_view flag, const std::string& text);

}  // namespace flat2d::maps::cli
