// Grammar of the single DBC statements the reader interprets (Vector "DBC File Format
// Documentation" 01/2007: message, signal, comment, value description and extended value
// type definitions). Internal to dbc.cpp, split out so each file keeps one job: dbc.cpp
// cuts the text into statements and builds the model; this file reads one statement. Whitespace between tokens
// is free (real files write "(1, 0)[0|255]" and "NAME: 7|32"). Errors say what was
// expected, without the location, which the caller adds.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hal/can/dbc.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can::dbc_internal {

// Identifier as written in a BO_/CM_/VAL_ statement, bit 31 = extended.
struct RawMessageId {
  std::uint32_t id = 0;
  bool extended = false;
  bool flagged = true;  // false: a 29-bit id > 0x7FF written without bit 31 (opendbc style)
};

// Interprets a DBC id: bit 31 marks a 29-bit id; an unflagged id above 0x7FF is read as
// 29-bit too (see `flagged`). Ids that fit neither are errors.
Result<RawMessageId> InterpretMessageId(std::uint64_t raw);

// The VECTOR__INDEPENDENT_SIG_MSG pseudo message that holds signals of no message.
inline constexpr std::uint64_t kIndependentSignalsId = 0xC0000000u;

struct MessageStatement {
  std::uint64_t raw_id = 0;
  DbcMessage message;  // without signals
};

// "BO_ <id> <name>: <dlc> <transmitter>".
Result<MessageStatement> ParseMessageStatement(std::string_view text);

// " SG_ <name> [M|m<n>] : <start>|<length>@<0|1><+|-> (<f>,<o>) [<min>|<max>] "<unit>" <rx>".
Result<DbcSignal> ParseSignalStatement(std::string_view text);

enum class CommentTarget : std::uint8_t { kOther, kMessage, kSignal };

struct CommentStatement {
  CommentTarget target = CommentTarget::kOther;
  std::uint64_t raw_id = 0;
  std::string signal;
  std::string text;
};

// "CM_ [BU_ <node>|BO_ <id>|SG_ <id> <signal>|EV_ <var>] "<text>";".
Result<CommentStatement> ParseCommentStatement(std::string_view text);

struct ValueNamesStatement {
  bool for_signal = false;  // false: an environment variable's table, ignored
  std::uint64_t raw_id = 0;
  std::string signal;
  std::vector<DbcValueName> names;
};

// "VAL_ <id> <signal> <value> "<name>" ... ;".
Result<ValueNamesStatement> ParseValueNamesStatement(std::string_view text);

struct ValueTypeStatement {
  std::uint64_t raw_id = 0;
  std::string signal;
  DbcValueType type = DbcValueType::kInteger;
};

// "SIG_VALTYPE_ <id> <signal> : <0|1|2>;".
Result<ValueTypeStatement> ParseValueTypeStatement(std::string_view text);

}  // namespace flat2d::hal::can::dbc_internal
