// Fakes of the GPIO HAL (hal/gpio/gpio_lines.hpp) for tests of the logic above it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "hal/gpio/gpio_lines.hpp"

namespace flat2d::hal::gpio::testing {

// Hands out queued events; Wait never sleeps.
class FakeEdgeSource final : public EdgeEventSource {
 public:
  // Reserves room so queuing in a test never reallocates under an allocation count.
  FakeEdgeSource() { events_.reserve(4096); }

  void Queue(TimeNs time_ns, Edge edge) { Queue(EdgeEvent{time_ns, edge, next_sequence_}); }
  void Queue(const EdgeEvent& event) {
    events_.push_back(event);
    next_sequence_ = event.sequence + 1;
  }
  std::size_t pending() const { return events_.size() - read_; }
  void FailNextRead(std::string message) { read_error_ = std::move(message); }

  Result<bool> Wait(TimeNs timeout_ns) override {
    waited_ns_ += timeout_ns;
    return pending() > 0;
  }

  Result<std::size_t> Read(std::span<EdgeEvent> out) override {
    if (read_error_) {
      Error error{*read_error_};
      read_error_.reset();
      return error;
    }
    const std::size_t count = std::min(out.size(), pending());
    std::copy_n(events_.begin() + static_cast<std::ptrdiff_t>(read_), count, out.begin());
    read_ += count;
    ++reads_;
    return count;
  }

  std::size_t reads() const { return reads_; }
  TimeNs waited_ns() const { return waited_ns_; }

 private:
  std::vector<EdgeEvent> events_;
  std::size_t read_ = 0;
  std::size_t reads_ = 0;
  std::uint64_t next_sequence_ = 0;
  TimeNs waited_ns_ = 0;
  std::optional<std::string> read_error_;
};

// Records every value written; can be told to fail writes.
class FakeOutput final : public DigitalOutput {
 public:
  explicit FakeOutput(bool initial = false) : value_(initial) {}

  Status Set(bool value) override {
    if (failures_left_ > 0) {
      --failures_left_;
      return MakeError("fake write failure");
    }
    value_ = value;
    writes_.push_back(value);
    return {};
  }
  bool value() const override { return value_; }

  void FailNextWrites(int count) { failures_left_ = count; }
  const std::vector<bool>& writes() const { return writes_; }

 private:
  bool value_;
  int failures_left_ = 0;
  std::vector<bool> writes_;
};

}  // namespace flat2d::hal::gpio::testing
