// SocketCanSource: option and Open errors everywhere; live reception against vcan0 where
// the kernel has AF_CAN and a vcan0 exists or can be created, skipping with the reason
// otherwise.
#include "hal/can/socketcan_source.hpp"

#include <gtest/gtest.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "tests/testing/allocation_counter.hpp"

namespace flat2d::hal::can {
namespace {

constexpr const char* kVcan = "vcan0";

// Runs `command` through the shell and returns what it printed (stdout and stderr).
std::string RunCommand(const std::string& command) {
  std::string output;
  std::FILE* pipe = ::popen(("(" + command + ") 2>&1").c_str(), "r");
  if (pipe == nullptr) return "popen failed";
  char buffer[256];
  while (std::fgets(buffer, sizeof(buffer), pipe) != nullptr) output += buffer;
  const int status = ::pclose(pipe);
  while (!output.empty() && output.back() == '\n') output.pop_back();
  const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return "'" + output + "' (exit status " + std::to_string(exit_code) + ")";
}

TimeNs RealtimeNow() {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return now.tv_sec * kNsPerSecond + now.tv_nsec;
}

TEST(SocketCanSource, BadOptionsAreRefusedBeforeAnySocketIsOpened) {
  SocketCanOptions options;
  options.interface_name = "";
  EXPECT_EQ(SocketCanSource::Open(options).error().message,
            "CAN interface name '' is not 1..15 characters (IFNAMSIZ)");
  options.interface_name = "a_name_too_long_";
  EXPECT_FALSE(SocketCanSource::Open(options).ok());
  options.interface_name = "can0";
  options.timeout_ms = -2;
  EXPECT_NE(SocketCanSource::Open(options).error().message.find("timeout -2 ms"),
            std::string::npos);
  options.timeout_ms = 10;
  options.ids = {{0x800, false}};
  EXPECT_NE(SocketCanSource::Open(options).error().message.find("0x800 is above 0x7FF"),
            std::string::npos);
}

TEST(SocketCanSource, OpenSaysWhetherTheKernelOrTheInterfaceIsMissing) {
  SocketCanOptions options;
  options.interface_name = "flat2dnone0";
  const Result<SocketCanSource> source = SocketCanSource::Open(options);
  ASSERT_FALSE(source.ok()) << "an interface named flat2dnone0 exists";
  const std::string& message = source.error().message;
  EXPECT_TRUE(message ==
                  "this kernel has no AF_CAN support (socket: Address family not supported by "
                  "protocol)" ||
              message == "no CAN interface 'flat2dnone0': No such device")
      << message;
}

// Sends frames on vcan0 through a second CAN_RAW socket; the kernel loops them back to
// every other socket on the interface.
class VcanSender {
 public:
  VcanSender() : socket_(::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW)) {
    const int on = 1;
    ::setsockopt(socket_.get(), SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof(on));
    sockaddr_can address{};
    address.can_family = AF_CAN;
    address.can_ifindex = static_cast<int>(::if_nametoindex(kVcan));
    bound_ = ::bind(socket_.get(), reinterpret_cast<const sockaddr*>(&address),
                    sizeof(address)) == 0;
  }
  bool bound() const { return bound_; }
  bool Send(canid_t id, std::uint8_t length, bool fd = false) {
    canfd_frame frame{};
    frame.can_id = id;
    frame.len = length;
    for (std::uint8_t i = 0; i < length; ++i) frame.data[i] = static_cast<std::uint8_t>(0xA0 + i);
    const std::size_t size = fd ? CANFD_MTU : CAN_MTU;
    return ::write(socket_.get(), &frame, size) == static_cast<ssize_t>(size);
  }

 private:
  net::SocketFd socket_;
  bool bound_ = false;
};

class SocketCanLive : public ::testing::Test {
 protected:
  static SocketCanOptions LiveOptions() {
    SocketCanOptions options;
    options.interface_name = kVcan;
    options.ids = {{0x123, false}, {0x1ABCDEF, true}};
    options.timeout_ms = 200;
    return options;
  }

  void SetUp() override {
    Result<SocketCanSource> probe = SocketCanSource::Open(LiveOptions());
    if (probe.ok()) return;
    const std::string opened = probe.error().message;
    const std::string created =
        RunCommand(std::string("ip link add dev ") + kVcan + " type vcan && ip link set up " +
                   kVcan);
    if (SocketCanSource::Open(LiveOptions()).ok()) return;
    GTEST_SKIP() << "no " << kVcan << " to test against: " << opened << "; `ip link add dev "
                 << kVcan << " type vcan` said: " << created;
  }
};

TEST_F(SocketCanLive, ReceivesOnlyConfiguredIdsWithKernelTimes) {
  Result<SocketCanSource> source = SocketCanSource::Open(LiveOptions());
  ASSERT_TRUE(source.ok()) << source.error().message;
  VcanSender sender;
  ASSERT_TRUE(sender.bound());
  const TimeNs before_ns = RealtimeNow();
  ASSERT_TRUE(sender.Send(0x124, 2));                        // not configured
  ASSERT_TRUE(sender.Send(0x123 | CAN_EFF_FLAG, 2));         // extended 0x123: not configured
  ASSERT_TRUE(sender.Send(0x123 | CAN_RTR_FLAG, 0));         // remote: filtered out
  ASSERT_TRUE(sender.Send(0x123, 3));
  ASSERT_TRUE(sender.Send(0x1ABCDEF | CAN_EFF_FLAG, 8));
  if (source->fd_enabled()) {
    ASSERT_TRUE(sender.Send(0x123, 12, true));
  }
  CanFrame frame;
  const std::uint64_t allocations_before = testing::AllocationCount();
  ASSERT_TRUE(source->Next(frame));
  EXPECT_EQ(testing::AllocationCount(), allocations_before) << "Next allocated";
  EXPECT_EQ(frame.id, 0x123u);
  EXPECT_FALSE(frame.extended);
  EXPECT_EQ(frame.length, 3);
  EXPECT_EQ(frame.data[2], 0xA2);
  EXPECT_EQ(frame.interface_name(), kVcan);
  EXPECT_GE(frame.time_ns, before_ns - kNsPerSecond);
  EXPECT_LE(frame.time_ns, RealtimeNow());
  ASSERT_TRUE(source->Next(frame));
  EXPECT_TRUE(frame.extended);
  EXPECT_EQ(frame.id, 0x1ABCDEFu);
  EXPECT_EQ(frame.length, 8);
  if (source->fd_enabled()) {
    ASSERT_TRUE(source->Next(frame));
    EXPECT_TRUE(frame.fd);
    EXPECT_EQ(frame.length, 12);
  }
  EXPECT_EQ(source->stats().without_kernel_time, 0u);
  EXPECT_EQ(source->stats().frames, source->fd_enabled() ? 3u : 2u);
}

TEST_F(SocketCanLive, NextGivesUpAfterTheTimeout) {
  SocketCanOptions options = LiveOptions();
  options.timeout_ms = 0;
  Result<SocketCanSource> source = SocketCanSource::Open(options);
  ASSERT_TRUE(source.ok()) << source.error().message;
  CanFrame frame;
  EXPECT_FALSE(source->Next(frame));
  EXPECT_EQ(source->stats().receive_errors, 0u);
}

}  // namespace
}  // namespace flat2d::hal::can
