#include "hal/velodyne/revolution.hpp"

#include <cmath>

#include "hal/velodyne/firing_timing.hpp"

namespace flat2d::hal::velodyne {

std::size_t MaxFansPerRevolution(Model model, ReturnMode mode, double rotation_hz) {
  const double fans_per_packet = 12.0 * TimingFor(model).fans_per_block;
  const double fans_per_second = fans_per_packet * PacketsPerSecond(model, mode);
  return static_cast<std::size_t>(std::ceil(1.1 * fans_per_second / rotation_hz));
}

RevolutionAssembler::RevolutionAssembler(const RevolutionOptions& options, Model model,
                                         ReturnMode mode)
    : cut_(options.cut_azimuth_rad),
      capacity_(options.max_fans > 0
                    ? options.max_fans
                    : MaxFansPerRevolution(model, mode, options.min_rotation_hz)) {
  for (Revolution& revolution : buffers_) revolution.fans.reserve(capacity_);
}

const Revolution* RevolutionAssembler::Add(std::span<const Fan> fans) {
  const Revolution* completed = nullptr;
  for (const Fan& fan : fans) {
    const AzimuthStep step = cut_.Next(fan.azimuth_rad);
    if (step.wraps) {
      completed = Publish(started_at_cut_);
      started_at_cut_ = true;
    }
    Revolution& current = buffers_[filling_];
    current.swept_azimuth_rad += step.forward_step_rad;
    if (current.fans.size() == capacity_) {
      ++current.dropped_fans;
      continue;
    }
    current.fans.push_back(fan);
    current.points += fan.num_points;
  }
  return completed;
}

const Revolution* RevolutionAssembler::Flush() {
  if (buffers_[filling_].fans.empty()) return nullptr;
  const Revolution* partial = Publish(false);
  started_at_cut_ = false;
  cut_.Reset();
  return partial;
}

const Revolution* RevolutionAssembler::Publish(bool complete) {
  Revolution& finished = buffers_[filling_];
  finished.complete = complete;
  finished.sequence = next_sequence_++;
  filling_ = 1 - filling_;
  Revolution& next = buffers_[filling_];
  next.fans.clear();  // keeps capacity: no allocation
  next.complete = false;
  next.points = 0;
  next.dropped_fans = 0;
  next.swept_azimuth_rad = 0.0;
  return &finished;
}

}  // namespace flat2d::hal::velodyne
