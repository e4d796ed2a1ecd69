#include "hal/carmen/carmen_line.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace flat2d::hal::carmen {
namespace {

// Whitespace-separated fields of a line, read left to right.
class Fields {
 public:
  explicit Fields(std::string_view line) : rest_(line) {}

  bool Next(std::string_view& field) {
    const std::size_t begin = rest_.find_first_not_of(" \t\r\n");
    if (begin == std::string_view::npos) return false;
    rest_.remove_prefix(begin);
    const std::size_t end = std::min(rest_.find_first_of(" \t\r\n"), rest_.size());
    field = rest_.substr(0, end);
    rest_.remove_prefix(end);
    return true;
  }

  bool Number(double& value) {
    std::string_view field;
    if (!Next(field)) return false;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    return error == std::errc() && end == field.data() + field.size() && std::isfinite(value);
  }

  bool Count(std::size_t& value, std::size_t max) {
    double number = 0.0;
    if (!Number(number) || number < 0.0 || number > static_cast<double>(max) ||
        number != std::floor(number)) {
      return false;
    }
    value = static_cast<std::size_t>(number);
    return true;
  }

  bool Pose(CarmenPose& pose) { return Number(pose.x) && Number(pose.y) && Number(pose.theta); }

 private:
  std::string_view rest_;
};

constexpr std::size_t kMaxBeams = 100000;

bool Ranges(Fields& fields, std::size_t count, std::vector<float>& ranges) {
  ranges.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    double range = 0.0;
    if (!fields.Number(range)) return false;
    ranges[i] = static_cast<float>(range);
  }
  return true;
}

Status ParseFlaser(Fields& fields, LaserScan& scan) {
  std::size_t count = 0;
  if (!fields.Count(count, kMaxBeams) || count < 2) return MakeError("FLASER: bad beam count");
  if (!Ranges(fields, count, scan.ranges)) return MakeError("FLASER: bad or missing range");
  if (!fields.Pose(scan.laser_pose)) return MakeError("FLASER: bad laser pose");
  if (!fields.Pose(scan.robot_pose)) return MakeError("FLASER: bad odometry pose");
  if (!fields.Number(scan.timestamp)) return MakeError("FLASER: bad timestamp");
  scan.message = CarmenMessage::kFlaser;
  scan.angle_min = -0.5 * std::numbers::pi;
  scan.angle_increment = std::numbers::pi / static_cast<double>(count % 2 == 1 ? count - 1 : count);
  scan.max_range = 0.0;
  return Status::Ok();
}

Status ParseRobotLaser(Fields& fields, LaserScan& scan) {
  double laser_type = 0.0;
  double fov = 0.0;
  double accuracy = 0.0;
  double remission_mode = 0.0;
  if (!fields.Number(laser_type) || !fields.Number(scan.angle_min) || !fields.Number(fov) ||
      !fields.Number(scan.angle_increment) || !fields.Number(scan.max_range) ||
      !fields.Number(accuracy) || !fields.Number(remission_mode)) {
    return MakeError("ROBOTLASER1: bad laser description");
  }
  std::size_t count = 0;
  if (!fields.Count(count, kMaxBeams)) return MakeError("ROBOTLASER1: bad beam count");
  if (!Ranges(fields, count, scan.ranges)) return MakeError("ROBOTLASER1: bad or missing range");
  std::size_t remissions = 0;
  if (!fields.Count(remissions, kMaxBeams)) return MakeError("ROBOTLASER1: bad remission count");
  for (std::size_t i = 0; i < remissions; ++i) {
    double ignored = 0.0;
    if (!fields.Number(ignored)) return MakeError("ROBOTLASER1: bad remission");
  }
  if (!fields.Pose(scan.laser_pose) || !fields.Pose(scan.robot_pose)) {
    return MakeError("ROBOTLASER1: bad pose");
  }
  double ignored = 0.0;
  for (int i = 0; i < 5; ++i) {  // tv, rv, forward and side safety distances, turn axis
    if (!fields.Number(ignored)) return MakeError("ROBOTLASER1: bad velocity or safety field");
  }
  if (!fields.Number(scan.timestamp)) return MakeError("ROBOTLASER1: bad timestamp");
  scan.message = CarmenMessage::kRobotLaser1;
  return Status::Ok();
}

}  // namespace

CarmenLineKind ClassifyCarmenLine(std::string_view line) {
  Fields fields(line);
  std::string_view word;
  if (!fields.Next(word)) return CarmenLineKind::kOther;
  if (word == "FLASER") return CarmenLineKind::kFlaser;
  if (word == "ROBOTLASER1") return CarmenLineKind::kRobotLaser1;
  if (word == "ODOM") return CarmenLineKind::kOdometry;
  return CarmenLineKind::kOther;
}

Status ParseCarmenLaserLine(std::string_view line, LaserScan& scan) {
  Fields fields(line);
  std::string_view word;
  if (!fields.Next(word)) return MakeError("empty line");
  if (word == "FLASER") return ParseFlaser(fields, scan);
  if (word == "ROBOTLASER1") return ParseRobotLaser(fields, scan);
  return MakeError("not a laser message: " + std::string(word.substr(0, 32)));
}

}  // namespace flat2d::hal::carmen
