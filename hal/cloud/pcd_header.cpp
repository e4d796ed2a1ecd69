#include "hal/cloud/pcd_header.hpp"

#include <algorithm>
#include <optional>

namespace flat2d::hal::cloud {
namespace {

struct Line {
  std::size_t number = 0;
  std::string_view keyword;
  std::vector<std::string_view> entries;
};

std::optional<ScalarKind> KindOf(std::string_view type) {
  if (type == "F") return ScalarKind::kFloat;
  if (type == "I") return ScalarKind::kSigned;
  if (type == "U") return ScalarKind::kUnsigned;
  return std::nullopt;
}

// Collects the header lines; Finish() checks them against each other.
class PcdHeaderParser {
 public:
  explicit PcdHeaderParser(std::string_view source) : source_(source) {}

  Status Apply(const Line& line) {
    const std::string_view k = line.keyword;
    if (k == "VERSION") return Version(line);
    if (k == "FIELDS" || k == "COLUMNS") return Fields(line);  // COLUMNS: v0.5
    if (k == "SIZE") return PerField(line, sizes_);
    if (k == "TYPE") return PerField(line, types_);
    if (k == "COUNT") return PerField(line, counts_);
    if (k == "WIDTH") return Dimension(line, width_);
    if (k == "HEIGHT") return Dimension(line, height_);
    if (k == "POINTS") {
      points_line_ = line;
      return Dimension(line, points_);
    }
    if (k == "VIEWPOINT") return Viewpoint(line);
    return Fail(line, "unknown keyword");
  }

  Status Data(const Line& line, PcdHeader& header) const {
    if (line.entries.size() != 1) return Fail(line, "expected ascii, binary or binary_compressed");
    const std::string_view kind = line.entries[0];
    if (kind == "ascii") {
      header.data = PcdData::kAscii;
    } else if (kind == "binary") {
      header.data = PcdData::kBinary;
    } else if (kind == "binary_compressed") {
      header.data = PcdData::kBinaryCompressed;
    } else {
      return Fail(line, "unknown data kind '" + std::string(kind) + "'");
    }
    header.data_line = line.number;
    return Status::Ok();
  }

  Status Finish(PcdHeader& header) const {
    if (const Status fields = FinishFields(header); !fields.ok()) return fields;
    return FinishDimensions(header);
  }

 private:
  Error Fail(const Line& line, const std::string& message) const {
    return MakeError(std::string(source_) + ": header line " + std::to_string(line.number) + " (" +
                     std::string(line.keyword) + "): " + message);
  }
  Error FailHeader(const std::string& message) const {
    return MakeError(std::string(source_) + ": header: " + message);
  }

  Status Version(const Line& line) const {
    static constexpr std::string_view kKnown[] = {"0.7", ".7", "0.6", ".6", "0.5", ".5"};
    for (const std::string_view known : kKnown) {
      if (line.entries.size() == 1 && line.entries[0] == known) return Status::Ok();
    }
    return Fail(line, "unsupported version (0.5 to 0.7 are read)");
  }

  Status Fields(const Line& line) {
    if (fields_) return Fail(line, "repeated");
    if (line.entries.empty()) return Fail(line, "no fields");
    fields_ = line;
    return Status::Ok();
  }

  Status PerField(const Line& line, std::optional<Line>& target) const {
    if (!fields_) return Fail(line, "before FIELDS");
    if (target) return Fail(line, "repeated");
    if (line.entries.size() != fields_->entries.size()) {
      return Fail(line, std::to_string(line.entries.size()) + " entries for " +
                            std::to_string(fields_->entries.size()) + " FIELDS");
    }
    target = line;
    return Status::Ok();
  }

  Status Dimension(const Line& line, std::optional<std::uint64_t>& target) const {
    if (target) return Fail(line, "repeated");
    std::uint64_t value = 0;
    if (line.entries.size() != 1 || !ParseCount(line.entries[0], value)) return Fail(line, "expected one count");
    if (value > kMaxPcdPoints) return Fail(line, std::to_string(value) + " is more than this reader takes");
    target = value;
    return Status::Ok();
  }

  Status Viewpoint(const Line& line) const {
    // The sensor pose of the cloud; PointCloud holds points in the sensor frame, so it is
    // checked but not kept.
    double value = 0.0;
    if (line.entries.size() != 7) return Fail(line, "expected 7 numbers: tx ty tz qw qx qy qz");
    for (const std::string_view entry : line.entries) {
      if (!ParseNumber(entry, value)) return Fail(line, "bad number '" + std::string(entry) + "'");
    }
    return Status::Ok();
  }

  Status FinishFields(PcdHeader& header) const {
    if (!fields_) return FailHeader("no FIELDS line");
    if (!sizes_) return FailHeader("no SIZE line");
    if (!types_) return FailHeader("no TYPE line");
    std::size_t offset = 0;
    for (std::size_t i = 0; i < fields_->entries.size(); ++i) {
      PcdField field;
      field.name = std::string(fields_->entries[i]);
      const std::string_view size = sizes_->entries[i];
      const std::string_view type = types_->entries[i];
      std::uint64_t value = 0;
      if (!ParseCount(size, value) || value > 8) {
        return Fail(*sizes_, "field " + field.name + ": bad size '" + std::string(size) + "'");
      }
      field.type.size = static_cast<int>(value);
      const std::optional<ScalarKind> kind = KindOf(type);
      if (!kind) return Fail(*types_, "field " + field.name + ": unknown type '" + std::string(type) + "'");
      field.type.kind = *kind;
      if (!IsDecodable(field.type)) {
        return Fail(*types_, "field " + field.name + ": " + std::string(type) + " with SIZE " +
                                      std::string(size) + " is no numeric type");
      }
      if (counts_) {
        const std::string_view count = counts_->entries[i];
        if (!ParseCount(count, value) || value == 0 || value > 1024) {
          return Fail(*counts_, "field " + field.name + ": bad count '" + std::string(count) + "'");
        }
        field.count = static_cast<int>(value);
      }
      field.offset = offset;
      offset += field.bytes();
      header.fields.push_back(std::move(field));
    }
    header.record_bytes = offset;
    return Status::Ok();
  }

  Status FinishDimensions(PcdHeader& header) const {
    std::optional<std::uint64_t> width = width_, height = height_, points = points_;
    // PCL's compatibility rules: no WIDTH and HEIGHT, or both 0, is an unorganized cloud.
    if (!width && !height) {
      width = points;
      height = 1;
    } else if (width == 0u && height == 0u) {
      width = points.value_or(0);
      height = 1;
    }
    if (!height) height = 1;
    if (!width) width = points;
    if (!width) return FailHeader("no POINTS, WIDTH or HEIGHT line");
    const std::uint64_t product = *width * *height;  // each at most kMaxPcdPoints: no overflow
    if (!points) points = product;
    if (product != *points) {
      const std::string message = std::to_string(*points) + " points, but WIDTH " + std::to_string(*width) +
                                  " x HEIGHT " + std::to_string(*height) + " = " + std::to_string(product);
      return points_line_ ? Fail(*points_line_, message) : FailHeader(message);
    }
    header.width = *width;
    header.height = *height;
    header.points = *points;
    return Status::Ok();
  }

  std::string_view source_;
  std::optional<Line> fields_;
  std::optional<Line> sizes_, types_, counts_;  // per-field lines
  std::optional<std::uint64_t> width_, height_, points_;
  std::optional<Line> points_line_;
};

}  // namespace

Result<PcdHeader> ParsePcdHeader(std::string_view bytes, std::string_view source_name) {
  PcdHeaderParser parser(source_name);
  PcdHeader header;
  std::size_t start = 0;
  for (std::size_t number = 1; start < bytes.size(); ++number) {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string_view::npos) end = bytes.size();
    const std::vector<std::string_view> words = SplitWords(bytes.substr(start, end - start));
    start = end + 1;
    if (words.empty() || words[0].front() == '#') continue;
    Line line{number, words[0], std::vector<std::string_view>(words.begin() + 1, words.end())};
    if (line.keyword == "DATA") {
      if (const Status data = parser.Data(line, header); !data.ok()) return data.error();
      if (const Status finished = parser.Finish(header); !finished.ok()) return finished.error();
      header.data_offset = std::min(start, bytes.size());
      return header;
    }
    if (const Status applied = parser.Apply(line); !applied.ok()) return applied.error();
  }
  return MakeError(std::string(source_name) + ": header: no DATA line");
}

}  // namespace flat2d::hal::cloud
