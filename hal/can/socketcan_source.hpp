// Live CAN frames from a SocketCAN CAN_RAW socket (Linux Documentation/networking/can.rst).
//
// The vehicle's wheel speeds and yaw rate arrive as a few ids among hundreds on the bus;
// the kernel should drop the rest, stamp what is kept on arrival, and say when it lost
// frames. Steps: (1) Open creates a non-blocking CAN_RAW socket, installs CAN_RAW_FILTER
// entries built from the configured ids (socketcan_frames.hpp), subscribes to every error
// class with CAN_RAW_ERR_FILTER, enables CAN_RAW_FD_FRAMES (best effort: kernels without
// CAN FD still deliver classic frames, fd_enabled() says which), SO_TIMESTAMPNS and
// SO_RXQ_OVFL, and binds to the interface found by if_nametoindex; (2) Next reads one
// frame with recvmsg into a preallocated canfd_frame and control buffer (no allocation
// per frame), waiting up to timeout_ms with poll when none is queued; (3) the frame gets
// its kernel receive time from the SCM_TIMESTAMPNS control message (CLOCK_REALTIME now if
// missing, counted) and the kernel's drop counter from SO_RXQ_OVFL; (4) error frames are
// classified and counted, never returned as data. Open fails with a message that says
// what is missing: AF_CAN support in the kernel, or the interface.
#pragma once

#include <linux/can.h>
#include <sys/socket.h>

#include <array>
#include <cstdint>
#include <ctime>
#include <string>
#include <vector>

#include "hal/can/can_frame.hpp"
#include "hal/can/socketcan_frames.hpp"
#include "hal/common/error.hpp"
#include "hal/net/socket_fd.hpp"

namespace flat2d::hal::can {

struct SocketCanOptions {
  std::string interface_name = "can0";
  std::vector<CanIdSpec> ids;  // deliver only these ids' data frames; empty: every frame
  bool fd_frames = true;       // accept CAN FD frames (CAN_RAW_FD_FRAMES)
  bool error_frames = true;    // subscribe to error frames, to count them
  int receive_buffer_bytes = 0;  // SO_RCVBUF request; 0 keeps the kernel default
  int timeout_ms = 10;  // how long Next waits when no frame is queued; 0: not at all; -1: forever
};

struct SocketCanStats {
  std::uint64_t frames = 0;               // data frames returned
  std::uint64_t fd_frames = 0;            // of them, CAN FD
  CanErrorCounts errors;                  // error frames received (not returned)
  std::uint64_t invalid = 0;              // reads of unexpected size (CAN XL, truncated)
  std::uint64_t kernel_drops = 0;         // SO_RXQ_OVFL: dropped by the kernel since Open
  std::uint64_t without_kernel_time = 0;  // stamped from CLOCK_REALTIME instead
  std::uint64_t receive_errors = 0;       // failed recvmsg/poll calls (e.g. ENETDOWN)
  int last_errno = 0;                     // of the latest receive error
};

class SocketCanSource final : public CanFrameSource {
 public:
  static Result<SocketCanSource> Open(const SocketCanOptions& options);

  SocketCanSource(SocketCanSource&&) noexcept = default;
  SocketCanSource& operator=(SocketCanSource&&) noexcept = default;
  ~SocketCanSource() override = default;

  // The next data frame, waiting up to timeout_ms; false if none arrived.
  bool Next(CanFrame& frame) override;

  const SocketCanStats& stats() const { return stats_; }
  bool fd_enabled() const { return fd_enabled_; }
  int fd() const { return socket_.get(); }

 private:
  enum class Received : std::uint8_t { kFrame, kSkipped, kNothing };
  // Room for the two control messages enabled: a timespec and a 32-bit drop counter.
  static constexpr std::size_t kControlBytes =
      CMSG_SPACE(sizeof(struct timespec)) + CMSG_SPACE(sizeof(std::uint32_t));

  SocketCanSource(net::SocketFd socket, const SocketCanOptions& options, bool fd_enabled);
  Received ReceiveOne(CanFrame& frame);
  bool WaitReadable();

  net::SocketFd socket_;
  std::array<char, kMaxInterfaceName> interface_{};
  int timeout_ms_ = 0;
  bool fd_enabled_ = false;
  canfd_frame raw_{};  // CANFD_MTU bytes: holds a classic or an FD frame
  alignas(cmsghdr) std::array<unsigned char, kControlBytes> control_{};
  SocketCanStats stats_;
};

}  // namespace flat2d::hal::can
