#include "hal/can/dbc.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <optional>
#include <sstream>

#include "hal/can/dbc_statements.hpp"
#include "hal/can/signal_decoder.hpp"

namespace flat2d::hal::can {
namespace {

using dbc_internal::RawMessageId;

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view TrimLeft(std::string_view text) {
  while (!text.empty() && IsBlank(text.front())) text.remove_prefix(1);
  return text;
}

std::string_view TrimRight(std::string_view text) {
  while (!text.empty() && IsBlank(text.back())) text.remove_suffix(1);
  return text;
}

// The statement keyword that starts `text` ("BU_:" gives "BU_").
std::string_view LeadingKeyword(std::string_view text) {
  text = TrimLeft(text);
  std::size_t end = 0;
  while (end < text.size() && !IsBlank(text[end]) && text[end] != ':' && text[end] != '\n') ++end;
  return text.substr(0, end);
}

// Statements that end with their line (messages, signals, version, new symbols, bit
// timing and nodes in the spec).
bool IsLineStatement(std::string_view keyword) {
  return keyword == "BO_" || keyword == "SG_" || keyword == "VERSION" || keyword == "BS_" ||
         keyword == "BU_" || keyword == "NS_";
}

// Statements that end with ';' (every other section of the spec, plus obsolete ones that
// NS_ blocks still list).
bool IsSemicolonStatement(std::string_view keyword) {
  static constexpr std::array<std::string_view, 29> kKeywords = {
      "CM_",           "BA_DEF_",        "BA_DEF_DEF_",    "BA_",         "BA_REL_",
      "BA_DEF_REL_",   "BA_DEF_DEF_REL_", "BA_DEF_SGTYPE_", "BA_SGTYPE_",  "VAL_",
      "VAL_TABLE_",    "SIG_VALTYPE_",   "BO_TX_BU_",      "EV_",         "ENVVAR_DATA_",
      "SGTYPE_",       "SGTYPE_VAL_",    "SIG_GROUP_",     "SIG_TYPE_REF_", "SIGTYPE_VALTYPE_",
      "BU_SG_REL_",    "BU_EV_REL_",     "BU_BO_REL_",     "CAT_DEF_",    "CAT_",
      "FILTER",        "EV_DATA_",       "NS_DESC_",       "SG_MUL_VAL_"};
  return std::find(kKeywords.begin(), kKeywords.end(), keyword) != kKeywords.end();
}

bool IsKeyword(std::string_view keyword) { return IsLineStatement(keyword) || IsSemicolonStatement(keyword); }

// Names are unique in a message, except once per multiplexer value; one switch at most.
Status CheckSiblings(const DbcMessage& message, const DbcSignal& signal) {
  for (const DbcSignal& other : message.signals) {
    if (signal.multiplex == DbcMultiplex::kSwitch && other.multiplex == DbcMultiplex::kSwitch) {
      return MakeError("second multiplexer switch " + signal.name + " (first: " + other.name +
                       "); extended multiplexing is not supported");
    }
    const bool both_multiplexed =
        other.multiplex == DbcMultiplex::kMultiplexed && signal.multiplex == DbcMultiplex::kMultiplexed;
    if (other.name == signal.name && (!both_multiplexed || other.multiplex_value == signal.multiplex_value)) {
      return MakeError("signal " + signal.name + " already defined on line " + std::to_string(other.line));
    }
  }
  return Status::Ok();
}

class Parser {
 public:
  Parser(std::string_view text, std::string_view source) : text_(text), source_(source) {
    dbc_.source = std::string(source);
  }

  Result<Dbc> Run() {
    while (pos_ < text_.size()) {
      if (Status status = Step(); !status.ok()) return status.error();
    }
    if (Status status = CloseMessage(); !status.ok()) return status.error();
    return std::move(dbc_);
  }

 private:
  Error At(int line, const std::string& what) const {
    return MakeError(std::string(source_) + ":" + std::to_string(line) + ": " + what);
  }

  // The rest of the current line; moves past its newline.
  std::string_view TakeLine() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    const std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    return line;
  }

  Status Step() {
    const int line_number = line_;
    const std::size_t line_start = pos_;
    const std::string_view line = TakeLine();
    const std::string_view content = TrimLeft(line);
    if (content.empty()) return Status::Ok();
    // An NS_ block lists one keyword per line, indented by Vector's tools.
    const std::string_view keyword = LeadingKeyword(content);
    if (in_symbol_block_ && (content.size() < line.size() || keyword == TrimRight(content))) {
      return Status::Ok();
    }
    in_symbol_block_ = false;
    if (content.starts_with("//")) return Status::Ok();  // opendbc-style comment line
    if (keyword == "SG_") return AddSignal(content, line_number);
    if (Status status = CloseMessage(); !status.ok()) return status;
    if (keyword == "BO_") return OpenMessage(content, line_number);
    if (keyword == "NS_") in_symbol_block_ = true;
    if (IsLineStatement(keyword)) return Status::Ok();
    if (!IsSemicolonStatement(keyword)) {
      return At(line_number, "unexpected '" + std::string(keyword.substr(0, 20)) +
                                 "'; expected a DBC keyword (BO_, SG_, CM_, BA_, VAL_, ...)");
    }
    pos_ = line_start + (content.data() - line.data());
    line_ = line_number;
    const auto statement = TakeStatement(keyword, line_number);
    if (!statement.ok()) return statement.error();
    return Interpret(keyword, *statement, line_number);
  }

  // From pos_ to the ';' outside quotes (or the end of the text); refuses unterminated
  // strings and a statement that runs into the next keyword, so a lost ';' cannot
  // swallow the messages that follow.
  Result<std::string_view> TakeStatement(std::string_view keyword, int first_line) {
    const std::size_t start = pos_;
    bool quoted = false;
    for (; pos_ < text_.size(); ++pos_) {
      const char c = text_[pos_];
      if (quoted && c == '\\' && pos_ + 1 < text_.size() && text_[pos_ + 1] != '\n') {
        ++pos_;  // an escaped character, e.g. \"
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == '\n') {
        ++line_;
        if (!quoted && IsKeyword(LeadingKeyword(text_.substr(pos_ + 1, 64)))) {
          return At(first_line, std::string(keyword) + " statement has no ';' before line " +
                                    std::to_string(line_) + "; expected ';' at its end");
        }
      } else if (c == ';' && !quoted) {
        ++pos_;
        return text_.substr(start, pos_ - start);
      }
    }
    if (quoted) return At(first_line, "string not terminated; expected a closing '\"'");
    return text_.substr(start);  // a last statement without ';' (strym's files end so)
  }

  Status Interpret(std::string_view keyword, std::string_view statement, int line);
  Status OpenMessage(std::string_view text, int line);
  Status AddSignal(std::string_view text, int line);
  Status CloseMessage();
  void ApplyComment(std::string_view statement, int line);
  void ApplyValueNames(std::string_view statement, int line);
  Status ApplyValueType(std::string_view statement, int line);
  DbcMessage* Find(std::uint64_t raw_id);
  DbcSignal* FindSignal(std::uint64_t raw_id, std::string_view name);

  std::string_view text_;
  std::string_view source_;
  std::size_t pos_ = 0;
  int line_ = 1;
  bool in_symbol_block_ = false;
  Dbc dbc_;
  bool message_open_ = false;  // SG_ lines belong to dbc_.messages.back()
  bool skipping_message_ = false;  // inside VECTOR__INDEPENDENT_SIG_MSG
};

Status Parser::Interpret(std::string_view keyword, std::string_view statement, int line) {
  if (keyword == "SG_MUL_VAL_") {
    return At(line, "SG_MUL_VAL_ (extended multiplexing) is not supported; expected simple "
                    "multiplexing with one M switch per message");
  }
  if (keyword == "CM_") ApplyComment(statement, line);
  if (keyword == "VAL_") ApplyValueNames(statement, line);
  if (keyword == "SIG_VALTYPE_") return ApplyValueType(statement, line);
  return Status::Ok();
}

Status Parser::OpenMessage(std::string_view text, int line) {
  auto statement = dbc_internal::ParseMessageStatement(text);
  if (!statement.ok()) return At(line, statement.error().message);
  if (statement->raw_id == dbc_internal::kIndependentSignalsId) {
    skipping_message_ = true;  // its signals belong to no frame
    return Status::Ok();
  }
  const auto id = dbc_internal::InterpretMessageId(statement->raw_id);
  if (!id.ok()) return At(line, "BO_ " + statement->message.name + ": " + id.error().message);
  DbcMessage& message = statement->message;
  message.id = id->id;
  message.extended = id->extended;
  message.line = line;
  if (const DbcMessage* other = dbc_.FindMessage(message.id, message.extended)) {
    return At(line, "BO_ " + message.name + ": id " + std::to_string(statement->raw_id) +
                        " is already used by " + other->name + " (line " + std::to_string(other->line) + ")");
  }
  if (const DbcMessage* other = dbc_.FindMessage(message.name)) {
    return At(line, "BO_ " + message.name + ": name already used on line " + std::to_string(other->line));
  }
  if (!id->flagged) {
    dbc_.warnings.push_back(std::string(source_) + ":" + std::to_string(line) + ": BO_ " + message.name +
                            ": id " + std::to_string(message.id) +
                            " exceeds 11 bits without the extended flag (bit 31); read as a 29-bit id");
  }
  dbc_.messages.push_back(std::move(message));
  message_open_ = true;
  return Status::Ok();
}

Status Parser::AddSignal(std::string_view text, int line) {
  auto signal = dbc_internal::ParseSignalStatement(text);
  if (!message_open_ && !skipping_message_) {
    return At(line, "SG_ outside a message; expected a BO_ line before it");
  }
  DbcMessage* message = skipping_message_ ? nullptr : &dbc_.messages.back();
  const std::string context = message ? "BO_ " + message->name + ": " : "";
  if (!signal.ok()) return At(line, context + signal.error().message);
  if (!message) return Status::Ok();
  signal->line = line;
  const std::size_t bytes = SignalBytesNeeded(signal->start_bit, signal->length, signal->little_endian);
  if (bytes > message->dlc) {
    return At(line, context + "signal " + signal->name + " needs " + std::to_string(bytes) +
                        " bytes; expected it to fit in the message's " + std::to_string(message->dlc));
  }
  if (Status status = CheckSiblings(*message, *signal); !status.ok()) {
    return At(line, context + status.error().message);
  }
  message->signals.push_back(std::move(*signal));
  return Status::Ok();
}

// A multiplexed signal may precede its switch, so the check waits for the message's end.
Status Parser::CloseMessage() {
  skipping_message_ = false;
  if (!message_open_) return Status::Ok();
  message_open_ = false;
  const DbcMessage& message = dbc_.messages.back();
  if (message.MultiplexSwitch() != nullptr) return Status::Ok();
  for (const DbcSignal& signal : message.signals) {
    if (signal.multiplex == DbcMultiplex::kMultiplexed) {
      return At(signal.line, "BO_ " + message.name + ": signal " + signal.name + " is multiplexed (m" +
                                 std::to_string(signal.multiplex_value) +
                                 ") but the message has no multiplexer switch; expected one signal marked M");
    }
  }
  return Status::Ok();
}

DbcMessage* Parser::Find(std::uint64_t raw_id) {
  const auto id = dbc_internal::InterpretMessageId(raw_id);
  if (!id.ok()) return nullptr;
  for (DbcMessage& message : dbc_.messages) {
    if (message.id == id->id && message.extended == id->extended) return &message;
  }
  return nullptr;
}

DbcSignal* Parser::FindSignal(std::uint64_t raw_id, std::string_view name) {
  DbcMessage* message = Find(raw_id);
  if (message == nullptr) return nullptr;
  for (DbcSignal& signal : message->signals) {
    if (signal.name == name) return &signal;
  }
  return nullptr;
}

// Comments are documentation: a malformed or dangling one is a warning, not an error.
void Parser::ApplyComment(std::string_view statement, int line) {
  const auto comment = dbc_internal::ParseCommentStatement(statement);
  const std::string where = std::string(source_) + ":" + std::to_string(line) + ": CM_ ";
  if (!comment.ok()) {
    dbc_.warnings.push_back(where + "ignored: " + comment.error().message);
    return;
  }
  if (comment->target == dbc_internal::CommentTarget::kMessage) {
    if (DbcMessage* message = Find(comment->raw_id)) message->comment = comment->text;
  } else if (comment->target == dbc_internal::CommentTarget::kSignal) {
    DbcMessage* message = Find(comment->raw_id);
    if (message == nullptr) return;
    for (DbcSignal& signal : message->signals) {
      if (signal.name == comment->signal) signal.comment = comment->text;
    }
  }
}

void Parser::ApplyValueNames(std::string_view statement, int line) {
  auto names = dbc_internal::ParseValueNamesStatement(statement);
  if (!names.ok()) {
    dbc_.warnings.push_back(std::string(source_) + ":" + std::to_string(line) + ": VAL_ ignored: " +
                            names.error().message);
    return;
  }
  if (!names->for_signal) return;
  if (DbcSignal* signal = FindSignal(names->raw_id, names->signal)) signal->value_names = std::move(names->names);
}

// The value type changes what the raw bits mean, so a bad one is an error.
Status Parser::ApplyValueType(std::string_view statement, int line) {
  const auto type = dbc_internal::ParseValueTypeStatement(statement);
  if (!type.ok()) return At(line, "SIG_VALTYPE_: " + type.error().message);
  DbcSignal* signal = FindSignal(type->raw_id, type->signal);
  if (signal == nullptr) return At(line, "SIG_VALTYPE_ names unknown signal " + type->signal);
  const std::uint8_t needed = type->type == DbcValueType::kFloat32 ? 32 : 64;
  if (type->type != DbcValueType::kInteger && signal->length != needed) {
    return At(line, "SIG_VALTYPE_ " + type->signal + ": expected a " + std::to_string(needed) +
                        "-bit signal for an IEEE value, found " + std::to_string(signal->length) + " bits");
  }
  signal->value_type = type->type;
  return Status::Ok();
}

}  // namespace

const DbcSignal* DbcMessage::FindSignal(std::string_view signal_name) const {
  for (const DbcSignal& signal : signals) {
    if (signal.name == signal_name) return &signal;
  }
  return nullptr;
}

const DbcSignal* DbcMessage::MultiplexSwitch() const {
  for (const DbcSignal& signal : signals) {
    if (signal.multiplex == DbcMultiplex::kSwitch) return &signal;
  }
  return nullptr;
}

const DbcMessage* Dbc::FindMessage(std::uint32_t id, bool extended) const {
  for (const DbcMessage& message : messages) {
    if (message.id == id && message.extended == extended) return &message;
  }
  return nullptr;
}

const DbcMessage* Dbc::FindMessage(std::string_view name) const {
  for (const DbcMessage& message : messages) {
    if (message.name == name) return &message;
  }
  return nullptr;
}

Result<Dbc> LoadDbc(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return MakeError(path.string() + ": cannot open DBC file");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return MakeError(path.string() + ": read error");
  return ParseDbc(text.str(), path.filename().string());
}

Result<Dbc> ParseDbc(std::string_view text, std::string_view source_name) {
  return Parser(text, source_name).Run();
}

}  // namespace flat2d::hal::can
