// Where one revolution ends: the azimuth stream of a spinning sensor wraps past a cut angle.
//
// A wrap is a backward step of the azimuth, measured relative to the cut, of more than
// 90 degrees: jitter and the two returns of a dual-return firing step back a little and never
// trigger it, and a FOV-limited sensor whose azimuth jumps inside a packet does only when the
// jump crosses the cut. Shared by the revolution assembler (which copies fans) and the grid
// builder (which consumes them as they arrive).
#pragma once

namespace flat2d::hal::velodyne {

struct AzimuthStep {
  bool wraps = false;             // this fan starts a new revolution
  double forward_step_rad = 0.0;  // azimuth swept since the previous fan (0 on a wrap or jitter)
};

class AzimuthCut {
 public:
  explicit AzimuthCut(double cut_azimuth_rad = 0.0);

  AzimuthStep Next(float azimuth_rad);
  // Forgets the previous azimuth (a new stream).
  void Reset() { have_previous_ = false; }

 private:
  double cut_azimuth_rad_;
  bool have_previous_ = false;
  double previous_relative_rad_ = 0.0;
};

}  // namespace flat2d::hal::velodyne
