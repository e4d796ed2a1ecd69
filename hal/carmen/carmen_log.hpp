// Reading 2D laser scans from CARMEN logs (plain or gzip), the format of the classic 2D
// SLAM benchmark logs (Radish, the Freiburg SLAM evaluation, GMapping's corrected logs).
//
// CarmenLogReader returns the laser messages of a log in file order: FLASER (old front
// laser: "FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_ts host logger_ts", a
// 180-degree scan starting at -90 degrees, spaced pi/n for even n and pi/(n-1) for odd n so
// that 181 and 361 beams include both ends) and ROBOTLASER1 (which states its own start
// angle, field of view, resolution and maximum range). Steps: (1) read the file through
// zlib (which passes uncompressed files through unchanged) a line at a time, a line longer
// than kMaxCarmenLineBytes being skipped, not buffered; (2) keep the laser messages, count
// ODOM, PARAM and the rest as other; (3) a laser line that does not parse (a bad number, a
// count that does not match the fields) is counted, its line number and reason kept for the
// first kMaxRecordedCarmenErrors, and skipped, never fatal.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hal/common/error.hpp"

namespace flat2d::hal::carmen {

inline constexpr std::size_t kMaxCarmenLineBytes = 1 << 20;
inline constexpr std::size_t kMaxRecordedCarmenErrors = 16;

struct CarmenPose {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

enum class CarmenMessage { kFlaser, kRobotLaser1 };

struct LaserScan {
  CarmenMessage message = CarmenMessage::kFlaser;
  double timestamp = 0.0;        // the message's ipc timestamp, seconds
  double angle_min = 0.0;        // bearing of ranges[0] in the laser frame, radians
  double angle_increment = 0.0;  // radians between beams, counter-clockwise
  double max_range = 0.0;        // metres; 0 when the message does not say (FLASER)
  std::vector<float> ranges;     // metres
  CarmenPose laser_pose;         // in the log's world frame
  CarmenPose robot_pose;         // FLASER: its "odom" pose fields
};

struct CarmenMalformedLine {
  std::uint64_t line = 0;  // 1-based
  std::string reason;
};

struct CarmenLogStats {
  std::uint64_t lines = 0;
  std::uint64_t flaser = 0;
  std::uint64_t robotlaser = 0;
  std::uint64_t odometry = 0;   // ODOM lines (counted, not returned)
  std::uint64_t other = 0;      // PARAM, comments, blank lines, other messages
  std::uint64_t malformed = 0;  // laser lines that did not parse, and over-long lines
  std::vector<CarmenMalformedLine> first_malformed;  // the first kMaxRecordedCarmenErrors
};

class CarmenLogReader {
 public:
  static Result<CarmenLogReader> Open(const std::filesystem::path& path);
  static CarmenLogReader FromString(std::string text, std::string name = "in-memory log");

  CarmenLogReader(CarmenLogReader&&) noexcept;
  CarmenLogReader& operator=(CarmenLogReader&&) noexcept;
  ~CarmenLogReader();

  // The next laser scan; false at the end of the log (or on a read error: read_error()).
  bool Next(LaserScan& scan);

  const CarmenLogStats& stats() const { return stats_; }
  const std::string& read_error() const { return read_error_; }
  const std::string& name() const { return name_; }

 private:
  struct Source;
  CarmenLogReader(std::unique_ptr<Source> source, std::string name);
  bool NextLine();
  void CountMalformed(std::string reason);

  std::unique_ptr<Source> source_;
  std::string name_;
  std::string line_;
  CarmenLogStats stats_;
  std::string read_error_;
};

struct CarmenScans {
  std::vector<LaserScan> scans;
  CarmenLogStats stats;
};

// Every laser scan of the log at `path`.
Result<CarmenScans> ReadCarmenLaserScans(const std::filesystem::path& path);

}  // namespace flat2d::hal::carmen
