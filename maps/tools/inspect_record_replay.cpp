#include "maps/tools/inspect_record_replay.hpp"

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/net/datagram_source.hpp"
#include "hal/net/ipv4.hpp"
#include "hal/net/pcap_writer.hpp"
#include "hal/net/replay.hpp"
#include "hal/net/udp_receiver.hpp"
#include "hal/net/udp_sender.hpp"
#include "hal/velodyne/packet_layout.hpp"
#include "maps/tools/cli_args.hpp"

namespace flat2d::maps {
namespace {

using namespace flat2d::hal::net;

volatile std::sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

constexpr std::string_view kTool = "flat2d-inspect";

[[noreturn]] void Fail(int status, const std::string& message) { cli::Fail(kTool, status, message); }
double Number(std::string_view flag, const char* text) { return cli::ParseNumber(kTool, flag, text); }
std::uint32_t Address(std::string_view flag, const std::string& text) {
  return cli::ParseAddress(kTool, flag, text);
}
std::uint16_t Port(std::string_view flag, const char* text) {
  return static_cast<std::uint16_t>(cli::ParseInteger(kTool, flag, text, 0, 65535));
}
std::uint64_t Count(std::string_view flag, const char* text) {
  return static_cast<std::uint64_t>(cli::ParseInteger(kTool, flag, text, 0, INT64_MAX));
}

// Walks argv, handing each flag and its value to `on_flag`; returns the positional args.
template <typename OnFlag>
std::vector<std::string> Parse(int argc, char** argv, const char* usage, OnFlag on_flag) {
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << usage;
      std::exit(0);
    }
    if (arg.empty() || arg[0] != '-') {
      positional.emplace_back(arg);
      continue;
    }
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) Fail(1, std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (!on_flag(arg, value)) Fail(1, "unknown option " + std::string(arg) + "\n" + usage);
  }
  return positional;
}

constexpr const char* kReplayUsage = R"(usage: flat2d-inspect replay [options] CAPTURE
  --to ADDR[:PORT]  destination (default 127.0.0.1; datagrams keep their own port unless
                    PORT is given)
  --speed X         timing factor: 2 plays twice as fast, 0 as fast as possible (default 1)
  --count N         stop after N datagrams
  --all-ports       replay every UDP datagram, not only the sensor ports 2368 and 8308
  --outage FROM:S   a sensor outage: send nothing for S seconds of capture time from FROM
                    seconds into the capture, then resume on schedule
)";

constexpr const char* kRecordUsage = R"(usage: flat2d-inspect record [options] --out FILE.pcap
  --bind ADDR         local address to listen on (default 0.0.0.0)
  --port P            data port (default 2368)
  --position-port P   position port, 0 for none (default 8308)
  --multicast GROUP   join this IPv4 multicast group
  --source ADDR       keep only datagrams from this sensor address
  --rcvbuf BYTES      socket receive buffer (default 8 MiB)
  --seconds S         stop after S seconds (default: until SIGINT/SIGTERM)
  --count N           stop after N datagrams
)";

}  // namespace

int RunReplay(int argc, char** argv) {
  UdpSenderOptions sender_options;
  sender_options.allow_broadcast = true;
  ReplayOptions replay_options;
  replay_options.destination_ports = {hal::velodyne::kDefaultDataPort,
                                      hal::velodyne::kDefaultPositionPort};
  const auto positional = Parse(argc, argv, kReplayUsage, [&](std::string_view flag, auto value) {
    if (flag == "--to") {
      std::string to = value();
      if (const auto colon = to.find(':'); colon != std::string::npos) {
        sender_options.destination.port = Port(flag, to.c_str() + colon + 1);
        sender_options.keep_datagram_port = false;
        to.resize(colon);
      }
      sender_options.destination.address = Address(flag, to);
    } else if (flag == "--speed") {
      replay_options.speed = Number(flag, value());
    } else if (flag == "--count") {
      replay_options.max_datagrams = Count(flag, value());
    } else if (flag == "--all-ports") {
      replay_options.destination_ports.clear();
    } else if (flag == "--outage") {
      const std::string outage = value();
      const auto colon = outage.find(':');
      if (colon == std::string::npos) Fail(1, "--outage takes FROM:SECONDS, got " + outage);
      replay_options.outage_from_ns = static_cast<TimeNs>(Number(flag, outage.substr(0, colon).c_str()) * 1e9);
      replay_options.outage_ns = static_cast<TimeNs>(Number(flag, outage.c_str() + colon + 1) * 1e9);
    } else {
      return false;
    }
    return true;
  });
  if (positional.size() != 1) Fail(1, std::string("replay needs one capture\n") + kReplayUsage);
  auto source = OpenCapture(positional[0]);
  if (!source.ok()) Fail(2, source.error().message);
  auto sender = UdpSender::Open(sender_options);
  if (!sender.ok()) Fail(2, sender.error().message);
  MonotonicReplayClock clock;
  const ReplayStats stats = Replay(**source, *sender, clock, replay_options);
  std::cerr << "flat2d-inspect: sent " << stats.sent << " datagrams to "
            << FormatIpv4(sender_options.destination.address) << ", " << stats.send_errors
            << " send errors, " << stats.skipped << " skipped (other ports)";
  if (stats.withheld > 0) std::cerr << ", " << stats.withheld << " withheld (the outage)";
  std::cerr << "\n";
  if (stats.send_errors > 0) std::cerr << "flat2d-inspect: first error: " << stats.first_send_error << "\n";
  return stats.send_errors == 0 ? 0 : 2;
}

int RunRecord(int argc, char** argv) {
  UdpReceiverOptions data_options;
  data_options.port = hal::velodyne::kDefaultDataPort;
  data_options.receive_buffer_bytes = 8 << 20;
  std::uint16_t position_port = hal::velodyne::kDefaultPositionPort;
  std::optional<std::string> out;
  double seconds = 0.0;
  std::uint64_t max_count = 0;
  Parse(argc, argv, kRecordUsage, [&](std::string_view flag, auto value) {
    if (flag == "--out") out = value();
    else if (flag == "--bind") data_options.bind_address = Address(flag, value());
    else if (flag == "--port") data_options.port = Port(flag, value());
    else if (flag == "--position-port") position_port = Port(flag, value());
    else if (flag == "--multicast") data_options.multicast_group = Address(flag, value());
    else if (flag == "--source") data_options.source_filter = Address(flag, value());
    else if (flag == "--rcvbuf") data_options.receive_buffer_bytes = static_cast<int>(cli::ParseInteger(kTool, flag, value(), 0, 1 << 30));
    else if (flag == "--seconds") seconds = Number(flag, value());
    else if (flag == "--count") max_count = Count(flag, value());
    else return false;
    return true;
  });
  if (!out) Fail(1, std::string("record needs --out\n") + kRecordUsage);

  std::vector<UdpReceiver> receivers;
  auto data = UdpReceiver::Open(data_options);
  if (!data.ok()) Fail(2, data.error().message);
  receivers.push_back(std::move(data).value());
  if (position_port != 0) {
    UdpReceiverOptions position_options = data_options;
    position_options.port = position_port;
    auto position = UdpReceiver::Open(position_options);
    if (!position.ok()) Fail(2, position.error().message);
    receivers.push_back(std::move(position).value());
  }
  auto writer = PcapWriter::Create(*out);
  if (!writer.ok()) Fail(2, writer.error().message);

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  MonotonicReplayClock clock;
  const TimeNs deadline = seconds > 0 ? clock.Now() + static_cast<TimeNs>(seconds * 1e9) : 0;
  std::uint64_t written = 0;
  while (!g_stop && (deadline == 0 || clock.Now() < deadline) && (max_count == 0 || written < max_count)) {
    for (UdpReceiver& receiver : receivers) {
      for (const UdpDatagram& datagram : receiver.ReceiveBatch(20)) {
        if (Status status = writer->Write(datagram); !status.ok()) Fail(2, status.error().message);
        ++written;
      }
    }
  }
  if (Status closed = writer->Close(); !closed.ok()) Fail(2, closed.error().message);
  std::uint64_t kernel_drops = 0;
  for (const UdpReceiver& receiver : receivers) kernel_drops += receiver.stats().kernel_drops;
  std::cerr << "flat2d-inspect: wrote " << written << " datagrams to " << *out << ", kernel drops "
            << kernel_drops << "\n";
  return 0;
}

}  // namespace flat2d::maps
