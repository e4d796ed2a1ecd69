// Wall-clock and process CPU time of a span, for the registration peers' figures: wall time
// as flat2d-map register reports it, and CPU time over all threads beside it, which shows
// whether a library really ran on one thread (CPU about wall) or spread out (CPU above it).
#pragma once

#include <time.h>

#include <chrono>

namespace flat2d::localization::peers {

class SpanTimer {
 public:
  SpanTimer() : wall_(std::chrono::steady_clock::now()), cpu_(ProcessCpuSeconds()) {}

  double WallMs() const {
    return 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_).count();
  }
  double CpuMs() const { return 1e3 * (ProcessCpuSeconds() - cpu_); }

 private:
  static double ProcessCpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
  }

  std::chrono::steady_clock::time_point wall_;
  double cpu_;
};

}  // namespace flat2d::localization::peers
