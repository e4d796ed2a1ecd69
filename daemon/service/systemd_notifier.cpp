#include "daemon/service/systemd_notifier.hpp"

#include <systemd/sd-daemon.h>

namespace flat2d::daemon {

void SystemdNotifier::Ready() const { sd_notify(0, "READY=1"); }
void SystemdNotifier::Reloading() const { sd_notify(0, "RELOADING=1"); }
void SystemdNotifier::Stopping() const { sd_notify(0, "STOPPING=1"); }
void SystemdNotifier::Status(const std::string& status) const { sd_notify(0, ("STATUS=" + status).c_str()); }
void SystemdNotifier::WatchdogPing() const { sd_notify(0, "WATCHDOG=1"); }

std::optional<TimeNs> SystemdNotifier::WatchdogInterval() const {
  uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) <= 0) return std::nullopt;
  return static_cast<TimeNs>(usec) * kNsPerUs;
}

std::vector<hal::net::SocketFd> ActivatedSockets() {
  std::vector<hal::net::SocketFd> sockets;
  const int count = sd_listen_fds(1);
  for (int i = 0; i < count; ++i) {
    const int fd = SD_LISTEN_FDS_START + i;
    if (sd_is_socket(fd, AF_UNSPEC, SOCK_STREAM, 1) > 0) sockets.emplace_back(fd);
  }
  return sockets;
}

}  // namespace flat2d::daemon
