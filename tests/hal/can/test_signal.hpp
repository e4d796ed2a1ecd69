// A DBC signal built in code, for decoder and encoder tests.
#pragma once

#include <cstdint>
#include <string>

#include "hal/can/dbc.hpp"

namespace flat2d::hal::can::test {

inline DbcSignal Signal(std::uint16_t start, std::uint8_t length, bool intel, bool is_signed,
                        double factor = 1.0, double offset = 0.0) {
  DbcSignal signal;
  signal.name = std::string(1, 'S');  // not = "S": GCC 12 -O3 -Wrestrict false positive
  signal.start_bit = start;
  signal.length = length;
  signal.little_endian = intel;
  signal.is_signed = is_signed;
  signal.factor = factor;
  signal.offset = offset;
  return signal;
}

}  // namespace flat2d::hal::can::test
