// Revolution assembly: fans are collected in a fixed-capacity buffer until the azimuth
// wraps past a configurable cut angle, then the revolution is published.
//
// Two revolution buffers are allocated at construction (sized from the worst case of
// the model and return mode at the slowest rotation, see MaxFansPerRevolution) and
// swapped at each cut (azimuth_cut.hpp says what a wrap is), so steady-state assembly
// allocates nothing. Fans that do not fit are dropped and counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "hal/common/time.hpp"
#include "hal/velodyne/azimuth_cut.hpp"
#include "hal/velodyne/fan.hpp"
#include "hal/velodyne/model.hpp"

namespace flat2d::hal::velodyne {

struct Revolution {
  std::vector<Fan> fans;  // capacity fixed at construction; size = fans in this turn
  // True when both ends are cuts: a turn that began mid-rotation (start of a stream) or
  // ended without a wrap (end of a stream) is partial.
  bool complete = false;
  std::uint64_t sequence = 0;   // 0, 1, 2, ... per assembler
  int points = 0;               // returns with non-zero range
  int dropped_fans = 0;         // fans that did not fit in the buffer
  TimeNs start_ns() const { return fans.empty() ? 0 : fans.front().stamp_ns; }
  TimeNs end_ns() const { return fans.empty() ? 0 : fans.back().stamp_ns; }
  // Azimuth swept from the first to the last fan, summing forward steps (radians).
  double swept_azimuth_rad = 0.0;
};

struct RevolutionOptions {
  double cut_azimuth_rad = 0.0;  // where one revolution ends and the next begins
  std::size_t max_fans = 0;      // 0: MaxFansPerRevolution of the model and mode
  double min_rotation_hz = 5.0;  // sizes the buffer when max_fans is 0
};

// Upper bound of fans in one turn at the given rotation rate, with 10 % margin.
std::size_t MaxFansPerRevolution(Model model, ReturnMode mode, double rotation_hz);

class RevolutionAssembler {
 public:
  RevolutionAssembler(const RevolutionOptions& options, Model model, ReturnMode mode);

  // Adds fans (in time order). Returns the revolution this call completed, or nullptr.
  // The returned revolution stays valid until the next completion. At most one
  // revolution completes per call if `fans` spans less than a turn (one packet does).
  const Revolution* Add(std::span<const Fan> fans);

  // Ends the stream: publishes what was collected as a partial revolution (nullptr if
  // nothing was).
  const Revolution* Flush();

  std::size_t capacity() const { return capacity_; }

 private:
  const Revolution* Publish(bool complete);

  AzimuthCut cut_;
  std::size_t capacity_;
  Revolution buffers_[2];
  int filling_ = 0;
  bool started_at_cut_ = false;
  std::uint64_t next_sequence_ = 0;
};

}  // namespace flat2d::hal::velodyne
