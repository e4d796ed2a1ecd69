// Data packets decoded into Cartesian fans per second on one core, reported as a
// multiple of the HDL-32E line rate (1808 packets/s, the most packets any supported
// model sends in single-return mode). Packets are real captures from shared/data, so
// the mix of returns and zero distances is the sensors' own.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "hal/net/datagram_source.hpp"
#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/packet_decoder.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "tests/testing/data_path.hpp"
#include "tests/testing/velodyne_packet_builder.hpp"

namespace {

using namespace flat2d::hal;

std::vector<std::vector<std::uint8_t>> LoadDataPackets(const std::string& relative) {
  std::vector<std::vector<std::uint8_t>> packets;
  const auto path = flat2d::testing::FindData(relative);
  if (!path) return packets;
  auto source = net::OpenCapture(*path);
  if (!source.ok()) return packets;
  while (auto datagram = (*source)->Next()) {
    if (datagram->payload.size() == velodyne::kDataPacketSize) {
      packets.emplace_back(datagram->payload.begin(), datagram->payload.end());
    }
  }
  return packets;
}

void ReportLineRateMultiple(benchmark::State& state, std::size_t packets_done) {
  state.counters["packets_per_s"] =
      benchmark::Counter(static_cast<double>(packets_done), benchmark::Counter::kIsRate);
  state.counters["x_hdl32e_line_rate"] = benchmark::Counter(
      static_cast<double>(packets_done) / velodyne::PacketsPerSecond(velodyne::Model::kHdl32e,
                                                                      velodyne::ReturnMode::kStrongest),
      benchmark::Counter::kIsRate);
}

// Decoder alone: packet bytes to Cartesian fans.
void BM_DecodePackets(benchmark::State& state, const std::string& capture, velodyne::Model model) {
  const auto packets = LoadDataPackets(capture);
  if (packets.empty()) {
    state.SkipWithError(("real data not found: " + capture).c_str());
    return;
  }
  velodyne::PacketDecoder decoder(velodyne::DefaultLaserTable(model));
  velodyne::DecodedPacket decoded;
  std::size_t index = 0, done = 0;
  for (auto _ : state) {
    decoder.Decode(packets[index], decoded);
    benchmark::DoNotOptimize(decoded.fans[0].returns[0].xyz);
    index = index + 1 == packets.size() ? 0 : index + 1;
    ++done;
  }
  ReportLineRateMultiple(state, done);
}

// The whole front end: decode, sequence checks, absolute time, revolution assembly.
void BM_StreamPackets(benchmark::State& state, const std::string& capture) {
  auto packets = LoadDataPackets(capture);
  if (packets.empty()) {
    state.SkipWithError(("real data not found: " + capture).c_str());
    return;
  }
  const std::uint32_t first_us = velodyne::ReadU32(packets.front().data() + velodyne::kTimestampOffset);
  const std::uint32_t last_us = velodyne::ReadU32(packets.back().data() + velodyne::kTimestampOffset);
  const std::uint32_t lap_us = last_us - first_us + 553;  // one HDL-32E packet period after the last
  std::size_t revolutions = 0, done = 0;
  velodyne::VelodyneStream stream({}, [&](const velodyne::Revolution&) { ++revolutions; });
  // Replaying a short capture in a loop would look like a jump back in time at each lap,
  // so each lap moves the device timestamps on by the capture's length.
  net::UdpDatagram datagram;
  datagram.destination.port = velodyne::kDefaultDataPort;
  std::size_t index = 0;
  for (auto _ : state) {
    datagram.payload = packets[index];
    stream.Push(datagram);
    if (++index == packets.size()) {
      index = 0;
      for (auto& packet : packets) flat2d::testing::AdvanceDeviceTime(packet, lap_us);
    }
    ++done;
  }
  benchmark::DoNotOptimize(revolutions);
  ReportLineRateMultiple(state, done);
}

BENCHMARK_CAPTURE(BM_DecodePackets, hdl32e, "velodyne/hdl32e/rust-lidar-utils_hdl32_example.pcap",
                  velodyne::Model::kHdl32e);
BENCHMARK_CAPTURE(BM_DecodePackets, vlp16, "velodyne/vlp16/mrpt_sample_velodyne_vlp16_gps.pcap",
                  velodyne::Model::kVlp16);
BENCHMARK_CAPTURE(BM_DecodePackets, vlp16_dual,
                  "velodyne/vlp16/DERIVED_nebula_vlp16_dual_1673400471837873222.pcap",
                  velodyne::Model::kVlp16);
BENCHMARK_CAPTURE(BM_DecodePackets, vlp32c,
                  "velodyne/vlp32c/DERIVED_nebula_vlp32c_1713492677464078412.pcap",
                  velodyne::Model::kVlp32c);
BENCHMARK_CAPTURE(BM_StreamPackets, hdl32e, "velodyne/hdl32e/rust-lidar-utils_hdl32_example.pcap");

}  // namespace

BENCHMARK_MAIN();
