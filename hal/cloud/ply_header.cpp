#include "hal/cloud/ply_header.hpp"

#include <algorithm>

namespace flat2d::hal::cloud {
namespace {

std::optional<ScalarType> PlyTypeNamed(std::string_view name) {
  struct Named {
    std::string_view old_name, sized_name;
    ScalarType type;
  };
  static constexpr Named kTypes[] = {
      {"char", "int8", {ScalarKind::kSigned, 1}},     {"uchar", "uint8", {ScalarKind::kUnsigned, 1}},
      {"short", "int16", {ScalarKind::kSigned, 2}},   {"ushort", "uint16", {ScalarKind::kUnsigned, 2}},
      {"int", "int32", {ScalarKind::kSigned, 4}},     {"uint", "uint32", {ScalarKind::kUnsigned, 4}},
      {"float", "float32", {ScalarKind::kFloat, 4}},  {"double", "float64", {ScalarKind::kFloat, 8}},
  };
  for (const Named& named : kTypes) {
    if (name == named.old_name || name == named.sized_name) return named.type;
  }
  return std::nullopt;
}

class PlyHeaderParser {
 public:
  explicit PlyHeaderParser(std::string_view source) : source_(source) {}

  // One line after "ply"; sets `done` at end_header.
  Status Apply(std::size_t number, const std::vector<std::string_view>& words, bool& done) {
    number_ = number;
    const std::string_view keyword = words[0];
    if (keyword == "comment") return Status::Ok();
    if (keyword == "format") return Format(words);
    if (keyword == "obj_info") return ObjInfo(words);
    if (keyword == "element") return Element(words);
    if (keyword == "property") return Property(words);
    if (keyword != "end_header") return Fail("unknown keyword '" + std::string(keyword) + "'");
    if (!format_seen_) return Fail("no format line before end_header");
    done = true;
    header_.data_line = number;
    return Status::Ok();
  }

  PlyHeader& header() { return header_; }

 private:
  Error Fail(const std::string& message) const {
    return MakeError(std::string(source_) + ": header line " + std::to_string(number_) + ": " + message);
  }
  Error FailIn(std::string_view what, std::string_view name, const std::string& message) const {
    return MakeError(std::string(source_) + ": header line " + std::to_string(number_) + " (" + std::string(what) +
                     " " + std::string(name) + "): " + message);
  }

  Status Format(const std::vector<std::string_view>& words) {
    if (format_seen_) return Fail("repeated format");
    if (words.size() != 3 || words[2] != "1.0") return Fail("expected 'format <kind> 1.0'");
    if (words[1] == "ascii") {
      header_.format = PlyFormat::kAscii;
    } else if (words[1] == "binary_little_endian") {
      header_.format = PlyFormat::kBinaryLittleEndian;
    } else if (words[1] == "binary_big_endian") {
      header_.format = PlyFormat::kBinaryBigEndian;
    } else {
      return Fail("unknown format '" + std::string(words[1]) + "'");
    }
    format_seen_ = true;
    return Status::Ok();
  }

  // Keeps the range grid size of Stanford scans; other obj_info is free text.
  Status ObjInfo(const std::vector<std::string_view>& words) {
    if (words.size() < 2 || (words[1] != "num_cols" && words[1] != "num_rows")) return Status::Ok();
    std::uint64_t value = 0;
    if (words.size() != 3 || !ParseCount(words[2], value) || value == 0 || value > kMaxPlyElements) {
      return FailIn("obj_info", words[1], "expected one positive count");
    }
    (words[1] == "num_cols" ? header_.num_cols : header_.num_rows) = value;
    return Status::Ok();
  }

  Status Element(const std::vector<std::string_view>& words) {
    if (words.size() != 3) return Fail("expected 'element <name> <count>'");
    PlyElement element;
    element.name = std::string(words[1]);
    element.line = number_;
    if (!ParseCount(words[2], element.count) || element.count > kMaxPlyElements) {
      return FailIn("element", words[1], "bad count '" + std::string(words[2]) + "'");
    }
    header_.elements.push_back(std::move(element));
    return Status::Ok();
  }

  Status Property(const std::vector<std::string_view>& words) {
    if (header_.elements.empty()) return Fail("property before any element");
    const bool list = words.size() >= 2 && words[1] == "list";
    if (words.size() != (list ? 5u : 3u)) {
      return Fail(list ? "expected 'property list <count type> <item type> <name>'"
                       : "expected 'property <type> <name>'");
    }
    PlyProperty property;
    property.name = std::string(words.back());
    property.list = list;
    const std::optional<ScalarType> type = PlyTypeNamed(words[words.size() - 2]);
    if (!type) return FailIn("property", property.name, "unknown type '" + std::string(words[words.size() - 2]) + "'");
    property.type = *type;
    if (list) {
      const std::optional<ScalarType> count_type = PlyTypeNamed(words[2]);
      if (!count_type || !count_type->integer()) {
        return FailIn("property", property.name, "list count type '" + std::string(words[2]) + "' is no integer type");
      }
      property.count_type = *count_type;
    }
    header_.elements.back().properties.push_back(std::move(property));
    return Status::Ok();
  }

  std::string_view source_;
  std::size_t number_ = 0;
  bool format_seen_ = false;
  PlyHeader header_;
};

}  // namespace

Result<PlyHeader> ParsePlyHeader(std::string_view bytes, std::string_view source_name) {
  PlyHeaderParser parser(source_name);
  std::size_t start = 0;
  for (std::size_t number = 1; start < bytes.size(); ++number) {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string_view::npos) end = bytes.size();
    const std::vector<std::string_view> words = SplitWords(bytes.substr(start, end - start));
    start = end + 1;
    if (number == 1) {
      if (words.size() != 1 || words[0] != "ply") {
        return MakeError(std::string(source_name) + ": not a PLY file (no 'ply' line)");
      }
      continue;
    }
    if (words.empty()) continue;
    bool done = false;
    if (const Status line = parser.Apply(number, words, done); !line.ok()) return line.error();
    if (done) {
      parser.header().data_offset = std::min(start, bytes.size());
      return std::move(parser.header());
    }
  }
  return MakeError(std::string(source_name) + ": header: no end_header line");
}

}  // namespace flat2d::hal::cloud
