#include "hal/config/text_proto.hpp"

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

namespace flat2d::hal::config {
namespace {

// Keeps the first error the parser reports; later ones are usually consequences.
class FirstErrorCollector final : public google::protobuf::io::ErrorCollector {
 public:
  explicit FirstErrorCollector(std::string_view source_name) : source_name_(source_name) {}

  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    Record(line, column, message);
  }
  void AddWarning(int line, google::protobuf::io::ColumnNumber column,
                  const std::string& message) override {
    Record(line, column, "warning treated as error: " + message);
  }

  bool has_error() const { return !first_.empty(); }
  const std::string& first() const { return first_; }

 private:
  void Record(int line, google::protobuf::io::ColumnNumber column, const std::string& message) {
    if (has_error()) return;
    // The parser counts lines and columns from 0; editors count from 1.
    first_ = std::string(source_name_) + ":" + std::to_string(line + 1) + ":" +
             std::to_string(column + 1) + ": " + message;
  }

  std::string source_name_;
  std::string first_;
};

}  // namespace

Status ParseTextProto(std::string_view text, std::string_view source_name,
                      google::protobuf::Message& message) {
  std::unique_ptr<google::protobuf::Message> parsed(message.New());
  FirstErrorCollector errors(source_name);
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  parser.AllowUnknownField(false);
  parser.AllowUnknownExtension(false);
  const bool ok = parser.ParseFromString(std::string(text), parsed.get());
  if (!ok || errors.has_error()) {
    return MakeError(errors.has_error() ? errors.first()
                                        : std::string(source_name) + ": cannot parse");
  }
  message.CopyFrom(*parsed);
  return Status::Ok();
}

Status LoadTextProto(const std::filesystem::path& path, google::protobuf::Message& message) {
  std::ifstream file(path);
  if (!file) return MakeError(path.string() + ": cannot open");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return MakeError(path.string() + ": read error");
  return ParseTextProto(text.str(), path.string(), message);
}

}  // namespace flat2d::hal::config
