#include "hal/gpio/libgpiod_lines.hpp"

#include <fcntl.h>
#include <gpiod.h>
#include <sys/utsname.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <ctime>
#include <system_error>
#include <utility>

namespace flat2d::hal::gpio {
namespace {

using ChipPtr = std::unique_ptr<gpiod_chip, detail::ChipCloser>;

std::string ErrnoText(int err) { return std::error_code(err, std::generic_category()).message(); }

bool IsDecimal(std::string_view text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string ChipOpenMessage(const std::string& shown, int err) {
  // libgpiod reports a file that is not a gpiochip character device as ENOTTY (or ENODEV
  // when its device numbers disagree with sysfs); say so instead of "Inappropriate ioctl".
  if (err == ENOTTY || err == ENODEV) return shown + ": not a GPIO chip character device";
  return shown + ": " + ErrnoText(err);
}

// Number -> /dev/gpiochipN; anything with a slash -> a path; else a /dev name, then a label
// (labels are tried only when no /dev entry has that name, and the name's error is kept).
Result<ChipPtr> OpenChip(const std::string& descriptor) {
  if (descriptor.empty()) return MakeError("GPIO chip not configured (empty chip name)");
  std::string shown = descriptor;
  gpiod_chip* chip = nullptr;
  int err = 0;
  if (IsDecimal(descriptor)) {
    unsigned number = 0;
    const auto [end, ec] =
        std::from_chars(descriptor.data(), descriptor.data() + descriptor.size(), number);
    if (ec != std::errc() || end != descriptor.data() + descriptor.size()) {
      return MakeError("GPIO chip number out of range: " + descriptor);
    }
    shown = "gpiochip" + descriptor;
    chip = gpiod_chip_open_by_number(number);
    err = errno;
  } else if (descriptor.find('/') != std::string::npos) {
    chip = gpiod_chip_open(descriptor.c_str());
    err = errno;
  } else {
    chip = gpiod_chip_open_by_name(descriptor.c_str());
    err = errno;
    if (chip == nullptr && err == ENOENT) chip = gpiod_chip_open_by_label(descriptor.c_str());
  }
  if (chip == nullptr) return MakeError(ChipOpenMessage(shown, err));
  return ChipPtr(chip);
}

// Opens the chip and finds the line, not yet requested.
Result<detail::RequestedLine> FindLine(const LineAddress& address) {
  auto chip = OpenChip(address.chip);
  if (!chip.ok()) return chip.error();
  const std::string chip_name = gpiod_chip_name(chip->get());
  gpiod_line* line = nullptr;
  std::string description;
  if (!address.name.empty()) {
    line = gpiod_chip_find_line(chip->get(), address.name.c_str());
    if (line == nullptr) {
      const int err = errno;
      if (err == ENOENT) return MakeError("no line named '" + address.name + "' on " + chip_name);
      return MakeError("looking up line '" + address.name + "' on " + chip_name + ": " +
                       ErrnoText(err));
    }
    description = "line '" + address.name + "' (" + std::to_string(gpiod_line_offset(line)) +
                  ") on " + chip_name;
  } else {
    description = "line " + std::to_string(address.offset) + " on " + chip_name;
    line = gpiod_chip_get_line(chip->get(), address.offset);
    if (line == nullptr) {
      const int err = errno;
      if (err == EINVAL) {
        return MakeError(description + ": no such line (the chip has " +
                         std::to_string(gpiod_chip_num_lines(chip->get())) + " lines)");
      }
      return MakeError(description + ": " + ErrnoText(err));
    }
  }
  detail::RequestedLine found;
  found.chip = std::move(*chip);
  found.line.reset(line);
  found.description = std::move(description);
  return found;
}

Error RequestError(const detail::RequestedLine& found, int err, std::string_view what) {
  if (err == EBUSY) {
    // The consumer in the line info names the holder: a kernel driver ("pps-gpio") or a
    // program's consumer string. Refresh it, since the lookup may predate the holder.
    const char* consumer = nullptr;
    if (gpiod_line_update(found.line.get()) == 0) consumer = gpiod_line_consumer(found.line.get());
    std::string message = found.description + " is busy (used by ";
    if (consumer != nullptr) {
      message.append("'").append(consumer).append("')");
    } else {
      message.append("an unnamed consumer)");
    }
    return MakeError(std::move(message));
  }
  return MakeError("requesting " + found.description + " as " + std::string(what) + ": " +
                   ErrnoText(err));
}

int RequestType(EdgeSelection edges) {
  switch (edges) {
    case EdgeSelection::kRising: return GPIOD_LINE_REQUEST_EVENT_RISING_EDGE;
    case EdgeSelection::kFalling: return GPIOD_LINE_REQUEST_EVENT_FALLING_EDGE;
    case EdgeSelection::kBoth: return GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES;
  }
  return GPIOD_LINE_REQUEST_EVENT_RISING_EDGE;
}

TimeNs ClockNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<TimeNs>(ts.tv_sec) * kNsPerSecond + ts.tv_nsec;
}

// Bracketing the realtime sample between two monotonic ones halves the error from being
// preempted between the calls.
TimeNs RealtimeMinusMonotonic() {
  const TimeNs before = ClockNs(CLOCK_MONOTONIC);
  const TimeNs realtime = ClockNs(CLOCK_REALTIME);
  const TimeNs after = ClockNs(CLOCK_MONOTONIC);
  return realtime - (before + (after - before) / 2);
}

EventClock RunningKernelEventClock() {
  utsname names{};
  if (uname(&names) != 0) return EventClock::kMonotonic;
  return V1EventClockForKernel(names.release);
}

}  // namespace

namespace detail {
void ChipCloser::operator()(gpiod_chip* chip) const { gpiod_chip_close(chip); }
void LineReleaser::operator()(gpiod_line* line) const { gpiod_line_release(line); }
}  // namespace detail

EventClock V1EventClockForKernel(std::string_view release) {
  int major = 0;
  int minor = 0;
  const char* const end = release.data() + release.size();
  const auto [after_major, ec_major] = std::from_chars(release.data(), end, major);
  if (ec_major != std::errc() || after_major == end || *after_major != '.') {
    return EventClock::kMonotonic;
  }
  const auto [after_minor, ec_minor] = std::from_chars(after_major + 1, end, minor);
  if (ec_minor != std::errc()) return EventClock::kMonotonic;
  const bool before_5_7 = major < 5 || (major == 5 && minor < 7);
  return before_5_7 ? EventClock::kRealtime : EventClock::kMonotonic;
}

LibgpiodEdgeInput::LibgpiodEdgeInput(detail::RequestedLine line, EventClock kernel_clock)
    : line_(std::move(line)), kernel_clock_(kernel_clock) {}

Result<LibgpiodEdgeInput> LibgpiodEdgeInput::Open(const EdgeInputOptions& options) {
  auto found = FindLine(options.line);
  if (!found.ok()) return found.error();
  gpiod_line_request_config config{};
  config.consumer = options.consumer.c_str();
  config.request_type = RequestType(options.edges);
  config.flags = options.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (gpiod_line_request(found->line.get(), &config, 0) != 0) {
    return RequestError(*found, errno, "an edge-event input");
  }
  // Non-blocking, so Read returns 0 instead of sleeping when nothing is pending.
  const int fd = gpiod_line_event_get_fd(found->line.get());
  const int flags = fd >= 0 ? fcntl(fd, F_GETFL) : -1;
  if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0) {
    return MakeError("making the event descriptor of " + found->description +
                     " non-blocking: " + ErrnoText(errno));
  }
  return LibgpiodEdgeInput(std::move(*found), RunningKernelEventClock());
}

Result<bool> LibgpiodEdgeInput::Wait(TimeNs timeout_ns) {
  timeout_ns = std::max<TimeNs>(timeout_ns, 0);
  const timespec timeout{static_cast<time_t>(timeout_ns / kNsPerSecond),
                         static_cast<long>(timeout_ns % kNsPerSecond)};
  const int ready = gpiod_line_event_wait(line_.line.get(), &timeout);
  if (ready < 0) {
    if (errno == EINTR) return false;
    return MakeError("waiting for events on " + line_.description + ": " + ErrnoText(errno));
  }
  return ready > 0;
}

Result<std::size_t> LibgpiodEdgeInput::Read(std::span<EdgeEvent> out) {
  // Stack scratch of the kernel FIFO's depth: libgpiod reads at most that many per call.
  std::array<gpiod_line_event, kMaxEventsPerRead> raw{};
  const TimeNs shift = kernel_clock_ == EventClock::kMonotonic ? RealtimeMinusMonotonic() : 0;
  std::size_t count = 0;
  while (count < out.size()) {
    const auto wanted = static_cast<unsigned>(std::min(out.size() - count, raw.size()));
    const int got = gpiod_line_event_read_multiple(line_.line.get(), raw.data(), wanted);
    if (got < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      return MakeError("reading events from " + line_.description + ": " + ErrnoText(errno));
    }
    for (int i = 0; i < got; ++i) {
      const gpiod_line_event& event = raw[static_cast<std::size_t>(i)];
      EdgeEvent& converted = out[count++];
      converted.time_ns =
          static_cast<TimeNs>(event.ts.tv_sec) * kNsPerSecond + event.ts.tv_nsec + shift;
      converted.edge =
          event.event_type == GPIOD_LINE_EVENT_RISING_EDGE ? Edge::kRising : Edge::kFalling;
      converted.sequence = next_sequence_++;
    }
    if (static_cast<unsigned>(got) < wanted) break;
  }
  return count;
}

LibgpiodOutput::LibgpiodOutput(detail::RequestedLine line, bool value)
    : line_(std::move(line)), value_(value) {}

Result<LibgpiodOutput> LibgpiodOutput::Open(const OutputOptions& options) {
  auto found = FindLine(options.line);
  if (!found.ok()) return found.error();
  if (gpiod_line_request_output(found->line.get(), options.consumer.c_str(),
                                options.initial_value ? 1 : 0) != 0) {
    return RequestError(*found, errno, "an output");
  }
  return LibgpiodOutput(std::move(*found), options.initial_value);
}

Status LibgpiodOutput::Set(bool value) {
  if (gpiod_line_set_value(line_.line.get(), value ? 1 : 0) != 0) {
    return MakeError("setting " + line_.description + " to " + (value ? "1" : "0") + ": " +
                     ErrnoText(errno));
  }
  value_ = value;
  return {};
}

}  // namespace flat2d::hal::gpio
