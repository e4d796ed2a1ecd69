// Time conventions: every timestamp in flat2d is int64 nanoseconds. Absolute times
// are nanoseconds since the Unix epoch (UTC); sensor-relative times say so in their
// name (e.g. ns_past_hour).
#pragma once

#include <chrono>
#include <cstdint>

namespace flat2d {

using TimeNs = std::int64_t;

inline constexpr TimeNs kNsPerUs = 1'000;
inline constexpr TimeNs kNsPerMs = 1'000'000;
inline constexpr TimeNs kNsPerSecond = 1'000'000'000;
inline constexpr TimeNs kNsPerHour = 3600 * kNsPerSecond;
inline constexpr TimeNs kNsPerDay = 24 * kNsPerHour;
inline constexpr double kSecondsPerNs = 1e-9;
// Velodyne's top-of-hour timestamps count microseconds in a uint32 (3.6e9 fits).
inline constexpr std::uint32_t kUsPerHour = static_cast<std::uint32_t>(kNsPerHour / kNsPerUs);

// Wall time since `start` in milliseconds, for the stage times tools report.
inline double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace flat2d
