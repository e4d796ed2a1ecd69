#include "hal/cloud/pcd_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hal/cloud/lzf.hpp"
#include "hal/cloud/pcd_header.hpp"

namespace flat2d::hal::cloud {
namespace {

// The fields the cloud keeps, as indices into PcdHeader::fields.
struct Channels {
  std::size_t x = 0, y = 0, z = 0;
  std::optional<std::size_t> intensity, ring;
};

// One point's kept values, before they go into the cloud.
struct PointValues {
  double x = 0.0, y = 0.0, z = 0.0, intensity = 0.0, ring = 0.0;
};

std::optional<std::size_t> FindField(const PcdHeader& header, std::string_view name) {
  for (std::size_t i = 0; i < header.fields.size(); ++i) {
    if (header.fields[i].name == name) return i;
  }
  return std::nullopt;
}

Result<std::size_t> Coordinate(const PcdHeader& header, std::string_view name, std::string_view source) {
  const std::optional<std::size_t> index = FindField(header, name);
  const std::string where = std::string(source) + ": field " + std::string(name) + ": ";
  if (!index) return MakeError(std::string(source) + ": FIELDS has no " + std::string(name));
  const PcdField& field = header.fields[*index];
  if (field.type.kind != ScalarKind::kFloat) return MakeError(where + "expected TYPE F (SIZE 4 or 8)");
  if (field.count != 1) return MakeError(where + "COUNT " + std::to_string(field.count) + ", expected 1");
  return *index;
}

Result<Channels> FindChannels(const PcdHeader& header, std::string_view source) {
  Channels channels;
  static constexpr std::string_view kAxes[] = {"x", "y", "z"};
  std::size_t* const coordinates[] = {&channels.x, &channels.y, &channels.z};
  for (int axis = 0; axis < 3; ++axis) {
    const Result<std::size_t> index = Coordinate(header, kAxes[axis], source);
    if (!index.ok()) return index.error();
    *coordinates[axis] = *index;
  }
  channels.intensity = FindField(header, "intensity");
  channels.ring = FindField(header, "ring");
  for (const std::optional<std::size_t>& index : {channels.intensity, channels.ring}) {
    if (index && header.fields[*index].count != 1) {
      return MakeError(std::string(source) + ": field " + header.fields[*index].name + ": COUNT " +
                       std::to_string(header.fields[*index].count) + ", expected 1");
    }
  }
  if (channels.ring && !header.fields[*channels.ring].type.integer()) {
    return MakeError(std::string(source) + ": field ring: TYPE F, expected an integer type (I or U)");
  }
  return channels;
}

PointCloud EmptyCloud(const Channels& channels, std::size_t reserve) {
  PointCloud cloud;
  cloud.points.reserve(reserve);
  if (channels.intensity) cloud.intensity.reserve(reserve);
  if (channels.ring) cloud.ring.reserve(reserve);
  return cloud;
}

Status Store(const PointValues& v, const Channels& channels, std::string_view source, PointCloud& cloud) {
  if (channels.ring) {
    if (!IsIntegerIn(v.ring, 0.0, 65535.0)) {
      return MakeError(std::string(source) + ": point " + std::to_string(cloud.points.size()) + ": ring " +
                       FormatNumber(v.ring) + " is not in 0..65535");
    }
    cloud.ring.push_back(static_cast<std::uint16_t>(v.ring));
  }
  if (channels.intensity) cloud.intensity.push_back(static_cast<float>(v.intensity));
  cloud.points.emplace_back(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
  return Status::Ok();
}

// Organized clouds (HEIGHT > 1): cell i holds point i, or -1 where it has no return.
void FillGrid(const PcdHeader& header, PointCloud& cloud) {
  if (header.height <= 1) return;
  cloud.grid_width = static_cast<int>(header.width);
  cloud.grid_height = static_cast<int>(header.height);
  cloud.grid.resize(cloud.points.size());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    cloud.grid[i] = cloud.points[i].array().isNaN().any() ? -1 : static_cast<std::int32_t>(i);
  }
}

// ---- DATA ascii ----------------------------------------------------------------------

// Where each field's values start on an ASCII point line, and how many values a line has.
struct AsciiLayout {
  std::vector<std::size_t> first_word;
  std::size_t words = 0;
};

AsciiLayout LayOutAscii(const PcdHeader& header) {
  AsciiLayout layout;
  for (const PcdField& field : header.fields) {
    layout.first_word.push_back(layout.words);
    layout.words += static_cast<std::size_t>(field.count);
  }
  return layout;
}

Status ParseAsciiPoint(const std::vector<std::string_view>& words, std::size_t line_number,
                       const AsciiLayout& layout, const PcdHeader& header, const Channels& channels,
                       std::string_view source, PointCloud& cloud) {
  const auto where = [&] { return std::string(source) + ": line " + std::to_string(line_number); };
  if (words.size() != layout.words) {
    return MakeError(where() + ": " + std::to_string(words.size()) + " values, FIELDS and COUNT say " +
                     std::to_string(layout.words));
  }
  PointValues v;
  const std::pair<std::optional<std::size_t>, double*> wanted[] = {
      {channels.x, &v.x}, {channels.y, &v.y}, {channels.z, &v.z}, {channels.intensity, &v.intensity},
      {channels.ring, &v.ring}};
  for (const auto& [field, value] : wanted) {
    if (!field) continue;
    const std::string_view word = words[layout.first_word[*field]];
    if (!ParseNumber(word, *value)) {
      return MakeError(where() + " (field " + header.fields[*field].name + "): bad number '" + std::string(word) + "'");
    }
  }
  return Store(v, channels, source, cloud);
}

Result<PointCloud> DecodeAscii(std::string_view text, const PcdHeader& header, const Channels& channels,
                               std::string_view source) {
  const AsciiLayout layout = LayOutAscii(header);
  // A point line holds at least one character and a separator per value.
  PointCloud cloud = EmptyCloud(channels, std::min<std::size_t>(header.points, text.size() / 2 + 1));
  std::size_t start = 0;
  std::size_t line_number = header.data_line;
  while (start < text.size() && cloud.points.size() < header.points) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::vector<std::string_view> words = SplitWords(text.substr(start, end - start));
    start = end + 1;
    ++line_number;
    if (words.empty()) continue;
    const Status point = ParseAsciiPoint(words, line_number, layout, header, channels, source, cloud);
    if (!point.ok()) return point.error();
  }
  if (cloud.points.size() < header.points) {
    return MakeError(std::string(source) + ": DATA ascii: " + std::to_string(cloud.points.size()) +
                     " point lines, POINTS says " + std::to_string(header.points));
  }
  return cloud;
}

// ---- DATA binary and binary_compressed ------------------------------------------------

// Decodes the kept fields of every point from `image`: row-major records (binary) or one
// column per field (binary_compressed, once decompressed).
Result<PointCloud> DecodeImage(const char* image, bool column_major, const PcdHeader& header,
                               const Channels& channels, std::string_view source) {
  const auto load = [&](std::size_t field_index, std::size_t point) {
    const PcdField& field = header.fields[field_index];
    const std::size_t at = column_major ? header.points * field.offset + point * field.bytes()
                                        : point * header.record_bytes + field.offset;
    return LoadScalar(image + at, field.type, /*big_endian=*/false);
  };
  PointCloud cloud = EmptyCloud(channels, header.points);
  for (std::size_t i = 0; i < header.points; ++i) {
    PointValues v{load(channels.x, i), load(channels.y, i), load(channels.z, i), 0.0, 0.0};
    if (channels.intensity) v.intensity = load(*channels.intensity, i);
    if (channels.ring) v.ring = load(*channels.ring, i);
    if (const Status stored = Store(v, channels, source, cloud); !stored.ok()) return stored.error();
  }
  return cloud;
}

Result<PointCloud> DecodeBinary(std::string_view data, const PcdHeader& header, const Channels& channels,
                                std::string_view source) {
  const std::uint64_t needed = header.points * header.record_bytes;
  if (data.size() < needed) {
    return MakeError(std::string(source) + ": DATA binary: " + std::to_string(data.size()) + " bytes for " +
                     std::to_string(header.points) + " points of " + std::to_string(header.record_bytes) +
                     " bytes");
  }
  return DecodeImage(data.data(), /*column_major=*/false, header, channels, source);
}

Result<PointCloud> DecodeCompressed(std::string_view data, const PcdHeader& header, const Channels& channels,
                                    std::string_view source) {
  const std::string where = std::string(source) + ": DATA binary_compressed: ";
  if (data.size() < 8) return MakeError(where + "no compressed and uncompressed sizes");
  const auto size_at = [&](std::size_t offset) {
    return static_cast<std::uint64_t>(LoadScalar(data.data() + offset, {ScalarKind::kUnsigned, 4}, false));
  };
  const std::uint64_t compressed = size_at(0);
  const std::uint64_t uncompressed = size_at(4);
  const std::uint64_t expected = header.points * header.record_bytes;
  if (compressed > data.size() - 8) {
    return MakeError(where + "compressed size " + std::to_string(compressed) + ", but " +
                     std::to_string(data.size() - 8) + " bytes follow");
  }
  if (uncompressed != expected) {
    return MakeError(where + "uncompressed size " + std::to_string(uncompressed) + ", but POINTS x record = " +
                     std::to_string(expected));
  }
  if (uncompressed > compressed * kLzfMaxExpansion) {
    return MakeError(where + std::to_string(compressed) + " bytes cannot expand to " + std::to_string(uncompressed));
  }
  std::vector<std::uint8_t> image(uncompressed);
  const auto* in = reinterpret_cast<const std::uint8_t*>(data.data() + 8);
  const std::optional<std::size_t> written = LzfDecompress(std::span(in, compressed), image);
  if (written != uncompressed) return MakeError(where + "malformed LZF data");
  return DecodeImage(reinterpret_cast<const char*>(image.data()), /*column_major=*/true, header, channels, source);
}

Result<PointCloud> DecodeData(std::string_view data, const PcdHeader& header, const Channels& channels,
                              std::string_view source) {
  switch (header.data) {
    case PcdData::kAscii: return DecodeAscii(data, header, channels, source);
    case PcdData::kBinary: return DecodeBinary(data, header, channels, source);
    case PcdData::kBinaryCompressed: break;
  }
  return DecodeCompressed(data, header, channels, source);
}

}  // namespace

Result<PointCloud> ParsePcd(std::string_view bytes, std::string_view source_name) {
  const Result<PcdHeader> header = ParsePcdHeader(bytes, source_name);
  if (!header.ok()) return header.error();
  const Result<Channels> channels = FindChannels(*header, source_name);
  if (!channels.ok()) return channels.error();
  Result<PointCloud> cloud = DecodeData(bytes.substr(header->data_offset), *header, *channels, source_name);
  if (cloud.ok()) FillGrid(*header, *cloud);
  return cloud;
}

Result<PointCloud> ReadPcd(const std::filesystem::path& path) {
  const Result<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.error();
  return ParsePcd(*bytes, path.string());
}

}  // namespace flat2d::hal::cloud
