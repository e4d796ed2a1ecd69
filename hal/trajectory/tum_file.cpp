#include "hal/trajectory/tum_file.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace flat2d::hal::trajectory {
namespace {

// Seconds with up to 9 decimals to integer nanoseconds without floating-point rounding.
bool ParseSeconds(std::string_view text, TimeNs& time_ns) {
  const std::size_t dot = text.find('.');
  const std::string_view whole = text.substr(0, dot);
  std::int64_t seconds = 0;
  auto [end, error] = std::from_chars(whole.data(), whole.data() + whole.size(), seconds);
  if (error != std::errc() || end != whole.data() + whole.size() || whole.empty() || seconds < 0) return false;
  std::int64_t fraction = 0;
  if (dot != std::string_view::npos) {
    std::string digits(text.substr(dot + 1));
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) {
      return false;
    }
    digits.resize(9, '0');
    std::from_chars(digits.data(), digits.data() + digits.size(), fraction);
  }
  if (seconds > (std::int64_t{1} << 33)) return false;  // beyond year 2242: not a timestamp
  time_ns = seconds * kNsPerSecond + fraction;
  return true;
}

bool ParseDouble(std::string_view text, double& value) {
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

std::string Where(std::string_view source, std::size_t line) {
  return std::string(source) + ":" + std::to_string(line) + ": ";
}

}  // namespace

Result<std::vector<StampedPose>> ParseTum(std::string_view text, std::string_view source_name) {
  std::vector<StampedPose> poses;
  std::size_t line_number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::array<std::string_view, 8> fields;
    std::size_t count = 0;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r' || line[i] == ',')) ++i;
      if (i == line.size()) break;
      const std::size_t field_start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != ',') ++i;
      if (count == fields.size()) return MakeError(Where(source_name, line_number) + "more than 8 fields");
      fields[count++] = line.substr(field_start, i - field_start);
    }
    if (count == 0) continue;
    if (count != 8) return MakeError(Where(source_name, line_number) + "expected 8 fields: t x y z qx qy qz qw");
    StampedPose pose;
    if (!ParseSeconds(fields[0], pose.time_ns)) return MakeError(Where(source_name, line_number) + "bad time");
    std::array<double, 7> v{};
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!ParseDouble(fields[i + 1], v[i])) {
        return MakeError(Where(source_name, line_number) + "bad number '" + std::string(fields[i + 1]) + "'");
      }
    }
    Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      return MakeError(Where(source_name, line_number) + "quaternion is not unit length");
    }
    if (!poses.empty() && pose.time_ns <= poses.back().time_ns) {
      return MakeError(Where(source_name, line_number) + "time does not increase");
    }
    pose.world_T_body.linear() = q.normalized().toRotationMatrix();
    pose.world_T_body.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    poses.push_back(pose);
  }
  return poses;
}

Result<std::vector<StampedPose>> ReadTum(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return MakeError(path.string() + ": cannot open");
  std::stringstream contents;
  contents << in.rdbuf();
  return ParseTum(contents.str(), path.string());
}

Status WriteTum(const std::vector<StampedPose>& poses, const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return MakeError(path.string() + ": cannot open for writing");
  std::fprintf(file, "# timestamp tx ty tz qx qy qz qw\n");
  for (const StampedPose& pose : poses) {
    if (pose.time_ns < 0) {
      std::fclose(file);
      return MakeError(path.string() + ": a pose before the epoch (" + std::to_string(pose.time_ns) + " ns)");
    }
    Eigen::Quaterniond q(pose.world_T_body.linear());
    q.normalize();
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();
    const Eigen::Vector3d t = pose.world_T_body.translation();
    const TimeNs seconds = pose.time_ns / kNsPerSecond, fraction = pose.time_ns % kNsPerSecond;
    std::fprintf(file, "%lld.%09lld %.7f %.7f %.7f %.9f %.9f %.9f %.9f\n", static_cast<long long>(seconds),
                 static_cast<long long>(fraction), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  }
  const bool ok = std::ferror(file) == 0;
  if (std::fclose(file) != 0 || !ok) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

}  // namespace flat2d::hal::trajectory
