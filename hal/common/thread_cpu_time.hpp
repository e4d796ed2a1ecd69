// CPU time of the calling thread, for per-revolution CPU figures: what the thread itself
// spent, not wall time (which a busy neighbour on the core would inflate).
#pragma once

#include <time.h>

namespace flat2d {

inline double ThreadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace flat2d
