#include "hal/can/dbc_statements.hpp"

#include <charconv>
#include <cmath>
#include <optional>

namespace flat2d::hal::can::dbc_internal {
namespace {

constexpr std::uint64_t kExtendedFlag = 0x80000000u;
constexpr std::uint32_t kMaxStandardIdValue = 0x7FF;
constexpr std::uint32_t kMaxExtendedIdValue = 0x1FFFFFFF;
constexpr std::uint64_t kMaxDlc = 64;           // CAN FD
constexpr std::uint64_t kMaxStartBit = 64 * 8 - 1;
constexpr std::uint64_t kMaxSignalBits = 64;

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
bool IsIdentifierStart(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool IsIdentifierChar(char c) { return IsIdentifierStart(c) || (c >= '0' && c <= '9'); }
bool IsNumberChar(char c) {
  return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == 'e' || c == 'E';
}

// Reads tokens of one statement; every read skips the whitespace before it.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  bool AtEnd() { SkipSpace(); return pos_ >= text_.size(); }
  bool Consume(char c) {
    SkipSpace();
    if (pos_ >= text_.size() || text_[pos_] != c) return false;
    ++pos_;
    return true;
  }
  std::string_view Identifier() {
    SkipSpace();
    const std::size_t start = pos_;
    if (pos_ < text_.size() && IsIdentifierStart(text_[pos_])) {
      while (pos_ < text_.size() && IsIdentifierChar(text_[pos_])) ++pos_;
    }
    return text_.substr(start, pos_ - start);
  }
  std::optional<std::uint64_t> Unsigned() {
    const std::string_view token = NumberToken();
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
    return value;
  }
  std::optional<std::int64_t> Integer() {
    std::string_view token = NumberToken();
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
    return value;
  }
  // A finite decimal number ("-0.25", "1e-05", "+3"); inf/nan are refused.
  std::optional<double> Number() {
    std::string_view token = NumberToken();
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || error != std::errc() || end != token.data() + token.size() ||
        !std::isfinite(value)) {
      return std::nullopt;
    }
    return value;
  }
  // A "..." string; a backslash keeps the next character (tools write \" in comments).
  std::optional<std::string_view> Quoted() {
    if (!Consume('"')) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
    if (pos_ >= text_.size()) return std::nullopt;
    return text_.substr(start, pos_++ - start);
  }
  // The next characters, for error messages.
  std::string Next() {
    SkipSpace();
    if (pos_ >= text_.size()) return "end of statement";
    // Appended piecewise: GCC 12's -Wrestrict misfires on "'" + std::string(...).
    std::string next(1, '\'');
    next.append(text_.substr(pos_, 12)).push_back('\'');
    return next;
  }

 private:
  void SkipSpace() {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) ++pos_;
  }
  std::string_view NumberToken() {
    SkipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && IsNumberChar(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

Error Expected(Cursor& cursor, std::string_view what) {
  return MakeError("expected " + std::string(what) + ", found " + cursor.Next());
}

// "M", "m<n>" or "m<n>M" after a signal's name.
Status ReadMultiplexIndicator(std::string_view indicator, DbcSignal& signal) {
  if (indicator == "M") {
    signal.multiplex = DbcMultiplex::kSwitch;
    return Status::Ok();
  }
  if (indicator.size() >= 2 && indicator.front() == 'm') {
    std::string_view digits = indicator.substr(1);
    if (digits.back() == 'M') {
      return MakeError("signal " + signal.name + " is a multiplexed multiplexer ('" +
                       std::string(indicator) + "'); extended multiplexing is not supported");
    }
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(),
                                              signal.multiplex_value);
    if (error == std::errc() && end == digits.data() + digits.size()) {
      signal.multiplex = DbcMultiplex::kMultiplexed;
      return Status::Ok();
    }
  }
  return MakeError("signal " + signal.name + ": expected 'M', 'm<value>' or ':' after the name, found '" +
                   std::string(indicator) + "'");
}

// "<start>|<length>@<0|1><+|->".
Status ReadBitLayout(Cursor& cursor, DbcSignal& signal) {
  const auto start = cursor.Unsigned();
  if (!start || *start > kMaxStartBit) return Expected(cursor, "a start bit 0..511");
  if (!cursor.Consume('|')) return Expected(cursor, "'|' after the start bit");
  const auto length = cursor.Unsigned();
  if (!length || *length == 0 || *length > kMaxSignalBits) return Expected(cursor, "a length of 1..64 bits");
  if (!cursor.Consume('@')) return Expected(cursor, "'@' before the byte order");
  const bool intel = cursor.Consume('1');
  if (!intel && !cursor.Consume('0')) return Expected(cursor, "byte order 0 (Motorola) or 1 (Intel)");
  const bool is_signed = cursor.Consume('-');
  if (!is_signed && !cursor.Consume('+')) return Expected(cursor, "'+' (unsigned) or '-' (signed)");
  signal.start_bit = static_cast<std::uint16_t>(*start);
  signal.length = static_cast<std::uint8_t>(*length);
  signal.little_endian = intel;
  signal.is_signed = is_signed;
  return Status::Ok();
}

// "(<factor>,<offset>) [<min>|<max>] "<unit>" <receivers>".
Status ReadScaling(Cursor& cursor, DbcSignal& signal) {
  if (!cursor.Consume('(')) return Expected(cursor, "'(' before the factor");
  const auto factor = cursor.Number();
  if (!factor || !cursor.Consume(',')) return Expected(cursor, "<factor>,");
  const auto offset = cursor.Number();
  if (!offset || !cursor.Consume(')')) return Expected(cursor, "<offset>)");
  if (!cursor.Consume('[')) return Expected(cursor, "'[' before the minimum");
  const auto minimum = cursor.Number();
  if (!minimum || !cursor.Consume('|')) return Expected(cursor, "<minimum>|");
  const auto maximum = cursor.Number();
  if (!maximum || !cursor.Consume(']')) return Expected(cursor, "<maximum>]");
  const auto unit = cursor.Quoted();
  if (!unit) return Expected(cursor, "the unit as a quoted string");
  signal.factor = *factor;
  signal.offset = *offset;
  signal.minimum = *minimum;
  signal.maximum = *maximum;
  signal.unit = std::string(*unit);
  // Receivers: node names separated by ',' (the spec) or spaces (some tools); kept none.
  while (!cursor.AtEnd()) {
    if (cursor.Consume(',')) continue;
    if (cursor.Identifier().empty()) return Expected(cursor, "receiver node names");
  }
  return Status::Ok();
}

}  // namespace

Result<RawMessageId> InterpretMessageId(std::uint64_t raw) {
  RawMessageId id;
  if (raw & kExtendedFlag) {
    id.extended = true;
    if ((raw & ~kExtendedFlag) > kMaxExtendedIdValue) {
      return MakeError("message id " + std::to_string(raw) + " has bits beyond 29 bits after the extended flag");
    }
    id.id = static_cast<std::uint32_t>(raw & ~kExtendedFlag);
    return id;
  }
  if (raw > kMaxExtendedIdValue) return MakeError("message id " + std::to_string(raw) + " is out of range");
  id.id = static_cast<std::uint32_t>(raw);
  id.extended = raw > kMaxStandardIdValue;
  id.flagged = !id.extended;
  return id;
}

Result<MessageStatement> ParseMessageStatement(std::string_view text) {
  Cursor cursor(text);
  MessageStatement statement;
  DbcMessage& message = statement.message;
  if (cursor.Identifier() != "BO_") return Expected(cursor, "BO_");
  const auto id = cursor.Unsigned();
  if (!id) return Expected(cursor, "a decimal message id after BO_");
  statement.raw_id = *id;
  message.name = std::string(cursor.Identifier());
  if (message.name.empty()) return Expected(cursor, "the message name after its id");
  if (!cursor.Consume(':')) return Expected(cursor, "':' after the message name");
  const auto dlc = cursor.Unsigned();
  if (!dlc || *dlc > kMaxDlc) return Expected(cursor, "the message length in bytes (0..64)");
  message.dlc = static_cast<std::uint8_t>(*dlc);
  message.transmitter = std::string(cursor.Identifier());
  if (message.transmitter.empty()) return Expected(cursor, "the transmitter node");
  if (!cursor.AtEnd()) return Expected(cursor, "the end of the BO_ line");
  return statement;
}

Result<DbcSignal> ParseSignalStatement(std::string_view text) {
  Cursor cursor(text);
  DbcSignal signal;
  if (cursor.Identifier() != "SG_") return Expected(cursor, "SG_");
  signal.name = std::string(cursor.Identifier());
  if (signal.name.empty()) return Expected(cursor, "the signal name after SG_");
  if (!cursor.Consume(':')) {
    const std::string_view indicator = cursor.Identifier();
    if (Status status = ReadMultiplexIndicator(indicator, signal); !status.ok()) return status.error();
    if (!cursor.Consume(':')) return Expected(cursor, "':' after the multiplexer indicator");
  }
  if (Status status = ReadBitLayout(cursor, signal); !status.ok()) {
    return MakeError("signal " + signal.name + ": " + status.error().message);
  }
  if (Status status = ReadScaling(cursor, signal); !status.ok()) {
    return MakeError("signal " + signal.name + ": " + status.error().message);
  }
  return signal;
}

Result<CommentStatement> ParseCommentStatement(std::string_view text) {
  Cursor cursor(text);
  CommentStatement statement;
  if (cursor.Identifier() != "CM_") return Expected(cursor, "CM_");
  std::optional<std::string_view> comment = cursor.Quoted();
  if (!comment) {
    const std::string_view object = cursor.Identifier();
    if (object == "BO_" || object == "SG_") {
      const auto id = cursor.Unsigned();
      if (!id) return Expected(cursor, "a message id");
      statement.raw_id = *id;
      statement.target = object == "BO_" ? CommentTarget::kMessage : CommentTarget::kSignal;
      if (object == "SG_") statement.signal = std::string(cursor.Identifier());
    } else if (object == "BU_" || object == "EV_") {
      cursor.Identifier();
    } else {
      return Expected(cursor, "a string or BU_, BO_, SG_, EV_ after CM_");
    }
    comment = cursor.Quoted();
  }
  if (!comment) return Expected(cursor, "the comment as a quoted string");
  statement.text = std::string(*comment);
  cursor.Consume(';');
  if (!cursor.AtEnd()) return Expected(cursor, "';' after the comment");
  return statement;
}

Result<ValueNamesStatement> ParseValueNamesStatement(std::string_view text) {
  Cursor cursor(text);
  ValueNamesStatement statement;
  if (cursor.Identifier() != "VAL_") return Expected(cursor, "VAL_");
  const auto id = cursor.Unsigned();
  if (!id) return statement;  // "VAL_ <environment variable> ...": not ours
  statement.for_signal = true;
  statement.raw_id = *id;
  statement.signal = std::string(cursor.Identifier());
  if (statement.signal.empty()) return Expected(cursor, "the signal name");
  while (!cursor.Consume(';') && !cursor.AtEnd()) {
    const auto value = cursor.Integer();
    if (!value) return Expected(cursor, "an integer value or ';'");
    const auto name = cursor.Quoted();
    if (!name) return Expected(cursor, "the value's name as a quoted string");
    statement.names.push_back({*value, std::string(*name)});
  }
  if (!cursor.AtEnd()) return Expected(cursor, "the end after ';'");
  return statement;
}

Result<ValueTypeStatement> ParseValueTypeStatement(std::string_view text) {
  Cursor cursor(text);
  ValueTypeStatement statement;
  if (cursor.Identifier() != "SIG_VALTYPE_") return Expected(cursor, "SIG_VALTYPE_");
  const auto id = cursor.Unsigned();
  if (!id) return Expected(cursor, "a message id");
  statement.raw_id = *id;
  statement.signal = std::string(cursor.Identifier());
  if (statement.signal.empty()) return Expected(cursor, "the signal name");
  cursor.Consume(':');  // written by Vector's tools, left out by some others
  const auto type = cursor.Unsigned();
  if (!type || *type > 2) return Expected(cursor, "value type 0 (integer), 1 (float) or 2 (double)");
  statement.type = static_cast<DbcValueType>(*type);
  cursor.Consume(';');
  if (!cursor.AtEnd()) return Expected(cursor, "';'");
  return statement;
}

}  // namespace flat2d::hal::can::dbc_internal
