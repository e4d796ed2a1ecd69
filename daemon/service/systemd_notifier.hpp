// systemd integration through libsystemd (sd-daemon(3)): readiness, status and watchdog
// notifications for Type=notify, and the sockets of socket activation.
//
// Without NOTIFY_SOCKET (started by hand, or in tests) every call does nothing, so the
// daemon runs the same way under systemd and outside it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hal/common/time.hpp"
#include "hal/net/socket_fd.hpp"

namespace flat2d::daemon {

class SystemdNotifier {
 public:
  void Ready() const;                            // READY=1
  void Reloading() const;                        // RELOADING=1 (then Ready again)
  void Stopping() const;                         // STOPPING=1
  void Status(const std::string& status) const;  // STATUS=...
  void WatchdogPing() const;                     // WATCHDOG=1
  // WatchdogSec as systemd set it for this process (WATCHDOG_USEC), if any.
  std::optional<TimeNs> WatchdogInterval() const;
};

// The listening sockets systemd passed (LISTEN_FDS), taken over (and the environment
// variables unset so children do not inherit them).
std::vector<hal::net::SocketFd> ActivatedSockets();

}  // namespace flat2d::daemon
