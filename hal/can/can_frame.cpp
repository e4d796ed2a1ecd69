#include "hal/can/can_frame.hpp"

#include <algorithm>
#include <cstdio>

namespace flat2d::hal::can {
namespace {

constexpr std::array<std::uint8_t, 16> kFdLengths = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

}  // namespace

std::string_view CanFrame::interface_name() const {
  const auto end = std::find(interface.begin(), interface.end(), '\0');
  return {interface.data(), static_cast<std::size_t>(end - interface.begin())};
}

void CanFrame::set_interface_name(std::string_view name) {
  interface.fill('\0');
  const std::size_t count = std::min(name.size(), interface.size() - 1);
  std::copy_n(name.begin(), count, interface.begin());
}

std::uint8_t FdLengthFromDlc(std::uint8_t dlc) { return kFdLengths[dlc & 0x0F]; }

std::uint8_t FdRoundUpLength(std::size_t length) {
  for (std::uint8_t valid : kFdLengths) {
    if (valid >= length) return valid;
  }
  return kFdLengths.back();
}

bool IsValidFdLength(std::size_t length) {
  return std::find(kFdLengths.begin(), kFdLengths.end(), length) != kFdLengths.end();
}

std::array<char, 9> FormatCanId(const CanFrame& frame) {
  std::array<char, 9> text{};
  std::snprintf(text.data(), text.size(), frame.extended ? "%08X" : "%03X",
                static_cast<unsigned>(frame.id));
  return text;
}

}  // namespace flat2d::hal::can
