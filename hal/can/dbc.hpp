// Reader of Vector's DBC text format ("DBC File Format Documentation", Vector Informatik,
// version 01/2007): the message definitions (BO_) and signal definitions (SG_) a vehicle's
// odometry needs, their comments (CM_), value descriptions (VAL_) and extended value types
// (SIG_VALTYPE_: IEEE float/double). Everything else is skipped as whole statements.
//
// Steps: (1) split the text into statements: BO_, SG_, VERSION, BS_, BU_ end with their
// line, the NS_ block with its last keyword line, every other keyword at the ';' outside a
// quoted string, so a comment may span lines and contain "BO_"; '//' lines are comments.
// (2) BO_ <id> <name>: <dlc> <transmitter>: bit 31 of the id marks a 29-bit id; opendbc
// files also write 29-bit ids > 0x7FF without the flag (Honda's 0x33DA), read as extended
// with a warning; Vector's VECTOR__INDEPENDENT_SIG_MSG (0xC0000000) is skipped. (3) SG_
// <name> [M|m<n>] : <start>|<length>@<0|1><+|-> (<factor>,<offset>) [<min>|<max>] "<unit>"
// <receivers>; @1 is Intel (start = LSB), @0 Motorola (start = MSB in the sawtooth
// numbering where bit 7 of byte 0 is 7 and bit 0 of byte 1 is 8). Simple multiplexing is
// supported: one switch M per message, m<n> signals present only when the switch's raw
// value is n (strym's RAV4 DBC needs it). Extended multiplexing (m<n>M, several switches,
// SG_MUL_VAL_) is refused. (4) check that every signal fits in its message's DLC and that
// names and ids are unique. Any violation is an Error naming the source, the line and
// what was expected; nothing throws. Malformed CM_/VAL_ content is only a warning:
// comments are documentation, and real files carry broken ones.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hal/common/error.hpp"

namespace flat2d::hal::can {

// What a signal's raw bits are (SIG_VALTYPE_: 0 integer, 1 IEEE float, 2 IEEE double).
enum class DbcValueType : std::uint8_t { kInteger, kFloat32, kFloat64 };

enum class DbcMultiplex : std::uint8_t {
  kNone,         // always present
  kSwitch,       // "M": selects which multiplexed signals a frame carries
  kMultiplexed,  // "m<n>": present only when the switch's raw value is multiplex_value
};

struct DbcValueName {
  std::int64_t value = 0;
  std::string name;
};

struct DbcSignal {
  std::string name;
  // DBC bit numbering: bit b is bit b % 8 (LSB = 0) of byte b / 8. Intel: the signal's
  // LSB; Motorola: its MSB.
  std::uint16_t start_bit = 0;
  std::uint8_t length = 0;     // bits, 1..64
  bool little_endian = false;  // @1 Intel; @0 Motorola
  bool is_signed = false;      // '-': two's complement
  double factor = 1.0;         // physical = raw * factor + offset
  double offset = 0.0;
  double minimum = 0.0;        // [0|0] in many files means "not stated"
  double maximum = 0.0;
  std::string unit;
  DbcValueType value_type = DbcValueType::kInteger;
  DbcMultiplex multiplex = DbcMultiplex::kNone;
  std::uint64_t multiplex_value = 0;  // for kMultiplexed
  std::string comment;                // CM_ SG_
  std::vector<DbcValueName> value_names;  // VAL_
  int line = 0;                       // of its SG_ line, for later error messages
};

struct DbcMessage {
  std::uint32_t id = 0;   // 11- or 29-bit identifier, without the DBC's bit-31 flag
  bool extended = false;  // 29-bit identifier
  std::string name;
  std::uint8_t dlc = 0;   // payload bytes, 0..64
  std::string transmitter;
  std::vector<DbcSignal> signals;
  std::string comment;    // CM_ BO_
  int line = 0;

  // The first signal called `name` (multiplexed signals may share a name), or nullptr.
  const DbcSignal* FindSignal(std::string_view signal_name) const;
  // The "M" signal, or nullptr when the message is not multiplexed.
  const DbcSignal* MultiplexSwitch() const;
};

struct Dbc {
  std::string source;  // file name or caller's label, for error messages downstream
  std::vector<DbcMessage> messages;
  // Accepted oddities worth telling the integrator (e.g. ids read as extended).
  std::vector<std::string> warnings;

  const DbcMessage* FindMessage(std::uint32_t id, bool extended) const;
  const DbcMessage* FindMessage(std::string_view name) const;
};

// Reads and parses a DBC file; errors name the file and line.
Result<Dbc> LoadDbc(const std::filesystem::path& path);

// Parses DBC text; `source_name` prefixes error messages (usually the file name).
Result<Dbc> ParseDbc(std::string_view text, std::string_view source_name);

}  // namespace flat2d::hal::can
