// libFuzzer target: arbitrary bytes as a candump -l log into CandumpReader.
//
// Logs come from the field (cut recordings, edited by hand, binary junk appended); whatever
// the bytes, reading must end without a crash, a leak or undefined behaviour, every line
// must be accounted for exactly once, and every frame returned must be one the writer
// accepts (so a log read can always be written back).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "hal/can/candump_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace flat2d::hal::can;
  CandumpReader reader =
      CandumpReader::FromString(std::string(reinterpret_cast<const char*>(data), size));
  std::array<char, kMaxCandumpFormattedBytes> line{};
  std::uint64_t frames = 0;
  CanFrame frame;
  while (reader.Next(frame)) {
    ++frames;
    if (FormatCandumpLine(frame, {}, reader.last_direction(), line).size == 0) std::abort();
  }
  const CandumpReaderStats& stats = reader.stats();
  const std::uint64_t accounted =
      stats.frames + stats.ignored_lines + stats.drop_notices + stats.malformed;
  if (frames != stats.frames || accounted != stats.lines) std::abort();
  if (stats.first_malformed.size() > kMaxRecordedMalformedLines) std::abort();
  return 0;
}
