#include "hal/cloud/kitti_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>

#include "hal/cloud/scalar.hpp"

namespace flat2d::hal::cloud {
namespace {

// The scans in velodyne/, sorted by name (KITTI's names are the zero-padded frame numbers).
Result<std::vector<std::filesystem::path>> ScansIn(const std::filesystem::path& velodyne) {
  std::error_code error;
  std::vector<std::filesystem::path> scans;
  for (std::filesystem::directory_iterator it(velodyne, error), end; !error && it != end; it.increment(error)) {
    if (it->path().extension() == ".bin" && it->is_regular_file()) scans.push_back(it->path());
  }
  if (error) return MakeError(velodyne.string() + ": cannot list (" + error.message() + ")");
  if (scans.empty()) return MakeError(velodyne.string() + ": no .bin scan");
  std::sort(scans.begin(), scans.end());
  return scans;
}

}  // namespace

bool IsKittiSequence(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_directory(path / "velodyne", error);
}

Result<std::vector<TimeNs>> ParseKittiTimes(std::string_view text, std::string_view source_name) {
  std::vector<TimeNs> stamps;
  std::size_t line_start = 0;
  for (int line_number = 1; line_start < text.size(); ++line_number) {
    const std::size_t line_end = std::min(text.find('\n', line_start), text.size());
    const std::vector<std::string_view> words = SplitWords(text.substr(line_start, line_end - line_start));
    line_start = line_end + 1;
    if (words.empty()) continue;
    const std::string where = std::string(source_name) + ": line " + std::to_string(line_number);
    double seconds = 0.0;
    if (words.size() != 1 || !ParseNumber(words[0], seconds) || !std::isfinite(seconds) || seconds < 0.0) {
      return MakeError(where + ": expected one time in seconds, >= 0");
    }
    const auto stamp = static_cast<TimeNs>(std::llround(seconds * static_cast<double>(kNsPerSecond)));
    if (!stamps.empty() && stamp <= stamps.back()) return MakeError(where + ": times must increase");
    stamps.push_back(stamp);
  }
  return stamps;
}

Result<KittiSequence> OpenKittiSequence(const std::filesystem::path& directory) {
  if (!IsKittiSequence(directory)) return MakeError(directory.string() + ": no velodyne/ directory (not a KITTI sequence)");
  auto scans = ScansIn(directory / "velodyne");
  if (!scans.ok()) return scans.error();
  const std::filesystem::path times_path = directory / "times.txt";
  const Result<std::string> text = ReadFileBytes(times_path);
  if (!text.ok()) return text.error();
  auto stamps = ParseKittiTimes(*text, times_path.string());
  if (!stamps.ok()) return stamps.error();
  if (stamps->size() < scans->size()) {
    return MakeError(times_path.string() + ": " + std::to_string(stamps->size()) + " times for " +
                     std::to_string(scans->size()) + " scans");
  }
  stamps->resize(scans->size());
  return KittiSequence{std::move(*scans), std::move(*stamps)};
}

}  // namespace flat2d::hal::cloud
