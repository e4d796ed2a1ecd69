// libFuzzer target: arbitrary bytes as DBC text into ParseDbc, then every parsed signal
// decoded from a few frames through CompiledSignal and FrameDecoder.
//
// DBC files come from the integrator's hands (hand edits, exports of other tools, cut
// downloads); whatever the bytes, parsing must end with a model or an Error, without a
// crash, a leak or undefined behaviour. A model that parsed must also keep its promises:
// every signal compiles and fits in its message's DLC, a frame shorter than a signal
// needs yields no value, raw values fit their bit length, and the decoder accounts for
// every frame.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "hal/can/dbc.hpp"
#include "hal/can/frame_decoder.hpp"
#include "hal/can/signal_decoder.hpp"

namespace {

using flat2d::hal::can::CanFrame;
using flat2d::hal::can::CompiledSignal;
using flat2d::hal::can::DbcMessage;

void CheckSignals(const DbcMessage& message, const std::array<CanFrame, 3>& frames) {
  for (const auto& signal : message.signals) {
    auto compiled = CompiledSignal::Compile(signal);
    if (!compiled.ok() || compiled->bytes_needed() > message.dlc) std::abort();
    for (const CanFrame& frame : frames) {
      for (std::size_t length = 0; length <= frame.length; ++length) {
        const auto raw = compiled->Raw(frame.payload().first(length));
        if (raw.has_value() != (length >= compiled->bytes_needed())) std::abort();
        if (raw && signal.length < 64 && (*raw >> signal.length) != 0) std::abort();
        if (raw) static_cast<void>(compiled->Physical(*raw));
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto dbc = flat2d::hal::can::ParseDbc(text, "fuzz.dbc");
  if (!dbc.ok()) return 0;
  // Frames of each message's id: all zeros, all ones, and the input's first bytes.
  std::array<CanFrame, 3> frames{};
  frames[1].data.fill(0xFF);
  std::memcpy(frames[2].data.data(), data, std::min(size, frames[2].data.size()));
  auto decoder = flat2d::hal::can::FrameDecoder::Create(*dbc, flat2d::hal::can::AllSignals(*dbc));
  if (!decoder.ok()) std::abort();  // every name exists and every signal compiled
  for (const DbcMessage& message : dbc->messages) {
    for (CanFrame& frame : frames) {
      frame.id = message.id;
      frame.extended = message.extended;
      frame.fd = message.dlc > 8;
      frame.length = message.dlc;
      decoder->Decode(frame);
      frame.length = message.dlc / 2;  // short frames too
      decoder->Decode(frame);
      frame.length = message.dlc;
    }
    CheckSignals(message, frames);
  }
  const auto& stats = decoder->stats();
  if (stats.decoded + stats.ignored + stats.checksum_failures + stats.too_short != stats.frames) std::abort();
  return 0;
}
