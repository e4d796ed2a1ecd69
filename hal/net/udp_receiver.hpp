// Live UDP reception in batches with kernel receive timestamps (Velodyne port 2368).
//
// A LiDAR sends 750-6000 datagrams per second; one system call per datagram and a
// user-space clock read after a scheduling delay would both cost accuracy. Steps:
// (1) Open binds a non-blocking socket, sizes SO_RCVBUF (SO_RCVBUFFORCE when
// privileged, so rmem_max does not cap it), asks for SO_TIMESTAMPNS, SO_RXQ_OVFL and
// IP_PKTINFO control messages, optionally joins a multicast group, and preallocates
// every buffer a batch needs; (2) ReceiveBatch polls with a timeout and drains up to
// batch_size datagrams with one recvmmsg; (3) each datagram gets its kernel receive
// time (CLOCK_REALTIME now, if the kernel gave none) and its header destination
// address; truncated ones and ones from a foreign source are dropped and counted;
// (4) the kernel's drop counter is kept as the latest value seen.
// Caveat: Linux switches receive timestamping on lazily (a static key flipped from a
// work queue), so for the first milliseconds after timestamping sockets appear in a
// system where none were open, datagrams may be stamped when read, not on arrival.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "hal/common/error.hpp"
#include "hal/net/ipv4.hpp"
#include "hal/net/socket_fd.hpp"
#include "hal/net/udp_datagram.hpp"

namespace flat2d::hal::net {

struct UdpReceiverOptions {
  std::uint32_t bind_address = kIpv4Any;
  std::uint16_t port = 0;  // 0: the kernel picks one, see local_endpoint()
  // Requested SO_RCVBUF in bytes; 0 keeps the kernel default. Size it for the
  // longest stall the reader may have: e.g. 4 MiB holds ~0.5 s of HDL-32E data.
  int receive_buffer_bytes = 0;
  std::optional<std::uint32_t> multicast_group;  // join this group (224.0.0.0/4)
  std::uint32_t multicast_interface = kIpv4Any;  // local address of the interface
  // Keep only datagrams from this sender (e.g. the sensor's 192.168.1.201).
  std::optional<std::uint32_t> source_filter;
  bool reuse_address = false;  // SO_REUSEADDR, for several listeners on one group
  std::size_t batch_size = 64;             // datagrams per recvmmsg, 1..1024
  std::size_t max_datagram_bytes = 2048;   // larger ones are counted as truncated
};

struct UdpReceiverStats {
  std::uint64_t received = 0;            // datagrams returned
  std::uint64_t filtered_by_source = 0;  // dropped by source_filter
  std::uint64_t truncated = 0;           // larger than max_datagram_bytes, dropped
  std::uint64_t kernel_drops = 0;        // SO_RXQ_OVFL: dropped by the kernel since Open
  std::uint64_t errors = 0;              // failed poll/recvmmsg calls
  std::uint64_t without_kernel_time = 0; // stamped from CLOCK_REALTIME instead
};

struct ReceiveBuffers;  // preallocated recvmmsg state, defined in the .cpp

class UdpReceiver {
 public:
  static Result<UdpReceiver> Open(const UdpReceiverOptions& options);

  UdpReceiver(UdpReceiver&&) noexcept;
  UdpReceiver& operator=(UdpReceiver&&) noexcept;
  ~UdpReceiver();

  // Waits up to timeout_ms (0: don't wait, -1: forever) and returns what arrived,
  // possibly nothing. The datagrams and payloads stay valid until the next call.
  std::span<const UdpDatagram> ReceiveBatch(int timeout_ms);

  const UdpReceiverStats& stats() const { return stats_; }
  Ipv4Endpoint local_endpoint() const { return local_endpoint_; }
  // SO_RCVBUF as the kernel reports it (Linux doubles the request for bookkeeping).
  int receive_buffer_bytes() const { return receive_buffer_bytes_; }
  int fd() const { return socket_.get(); }

 private:
  UdpReceiver(SocketFd socket, const UdpReceiverOptions& options);
  std::optional<UdpDatagram> Accept(std::size_t index, TimeNs& fallback_time_ns);

  SocketFd socket_;
  UdpReceiverOptions options_;
  std::unique_ptr<ReceiveBuffers> buffers_;
  Ipv4Endpoint local_endpoint_;
  int receive_buffer_bytes_ = 0;
  UdpReceiverStats stats_;
};

}  // namespace flat2d::hal::net
