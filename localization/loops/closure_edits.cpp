#include "localization/loops/closure_edits.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "hal/cloud/scalar.hpp"

namespace flat2d::localization::loops {
namespace {

bool ParseIndex(std::string_view field, int& index) {
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), index);
  return error == std::errc() && end == field.data() + field.size() && index >= 0;
}

bool ParseFinite(std::string_view field, double& value) { return hal::cloud::ParseNumber(field, value) && std::isfinite(value); }

// One line's edit into `edits`; an empty string when it parsed, else the problem.
std::string ParseLine(const std::vector<std::string_view>& f, ClosureEdits& edits) {
  const bool add = f[0] == "add";
  if (!add && f[0] != "remove") return "unknown edit '" + std::string(f[0]) + "' (add or remove)";
  const std::size_t expected = add ? 10 : 3;
  if (f.size() != expected) {
    return std::string(f[0]) + " takes " + std::to_string(expected - 1) + " fields, found " + std::to_string(f.size() - 1);
  }
  int reference = 0, current = 0;
  if (!ParseIndex(f[1], reference) || !ParseIndex(f[2], current)) return "map indices are integers >= 0";
  if (!add) {
    edits.removals.emplace_back(reference, current);
    return {};
  }
  double v[7];
  for (int k = 0; k < 7; ++k) {
    if (!ParseFinite(f[static_cast<std::size_t>(3 + k)], v[k])) return "field " + std::to_string(4 + k) + " is not a number";
  }
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (std::abs(q.norm() - 1.0) > 1e-3) return "the quaternion is not unit length";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  edits.additions.push_back({reference, current, pose});
  return {};
}

}  // namespace

Result<ClosureEdits> ParseClosureEdits(std::string_view text, std::string_view source_name) {
  ClosureEdits edits;
  int line_number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++line_number;
    line = line.substr(0, line.find('#'));
    const std::vector<std::string_view> fields = hal::cloud::SplitWords(line);
    if (fields.empty()) continue;
    if (std::string problem = ParseLine(fields, edits); !problem.empty()) {
      return MakeError(std::string(source_name) + ": line " + std::to_string(line_number) + ": " + problem);
    }
  }
  return edits;
}

Result<ClosureEdits> ReadClosureEdits(const std::filesystem::path& path) {
  auto text = hal::cloud::ReadFileBytes(path);
  if (!text.ok()) return text.error();
  return ParseClosureEdits(*text, path.string());
}

}  // namespace flat2d::localization::loops
