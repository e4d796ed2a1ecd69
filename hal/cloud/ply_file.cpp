#include "hal/cloud/ply_file.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hal/cloud/ply_cursor.hpp"
#include "hal/cloud/ply_header.hpp"

namespace flat2d::hal::cloud {
namespace {

// Reads the elements of one file into a cloud, with either cursor.
template <typename Cursor>
class ElementReader {
 public:
  ElementReader(Cursor& cursor, std::string_view source) : cursor_(cursor), source_(source) {}

  Status Read(const PlyHeader& header, PointCloud& cloud) {
    for (const PlyElement& element : header.elements) {
      if (const Status fits = Fits(element); !fits.ok()) return fits;
      Status read = Status::Ok();
      if (element.name == "vertex") {
        read = ReadVertices(element, cloud);
      } else if (element.name == "range_grid") {
        read = ReadGrid(element, cloud);
      } else {
        read = SkipElement(element);
      }
      if (!read.ok()) return read;
    }
    return Status::Ok();
  }

 private:
  // What a vertex property goes into; kSkip for those the cloud does not keep.
  enum Slot { kX, kY, kZ, kIntensity, kNx, kNy, kNz, kSkip };

  Error Fail(const PlyElement& element, std::uint64_t index, const PlyProperty& property,
             const std::string& problem) const {
    return MakeError(std::string(source_) + ": " + cursor_.Where() + " (" + element.name + " " +
                     std::to_string(index) + ", property " + property.name + "): " + problem);
  }

  // Bounds what a hostile count can make us reserve or loop over.
  Status Fits(const PlyElement& element) const {
    const std::size_t min_bytes = Cursor::MinBytes(element);
    if (min_bytes == 0 || element.count <= cursor_.remaining() / min_bytes + 1) return Status::Ok();
    return MakeError(std::string(source_) + ": header line " + std::to_string(element.line) + " (element " +
                     element.name + "): " + std::to_string(element.count) + " instances cannot fit in the " +
                     std::to_string(cursor_.remaining()) + " bytes left");
  }

  // Reads one property: a scalar into `value`, a list's items past (`value` = count).
  bool ReadProperty(const PlyProperty& property, double& value, std::string& problem) {
    if (!cursor_.Next(property.list ? property.count_type : property.type, value, problem)) return false;
    if (!property.list) return true;
    if (!IsIntegerIn(value, 0.0, 4294967295.0)) {
      problem = "bad list count " + FormatNumber(value);
      return false;
    }
    return cursor_.Skip(property.type, static_cast<std::uint64_t>(value), problem);
  }

  Result<std::vector<Slot>> VertexSlots(const PlyElement& element) const {
    static constexpr std::string_view kNames[] = {"x", "y", "z", "intensity", "nx", "ny", "nz"};
    std::vector<Slot> slots(element.properties.size(), kSkip);
    bool found[kSkip] = {};
    for (std::size_t p = 0; p < slots.size(); ++p) {
      for (int s = kX; s < kSkip; ++s) {
        if (element.properties[p].name != kNames[s]) continue;
        if (element.properties[p].list) {
          return FailHeader(element, "property " + std::string(kNames[s]) + " is a list");
        }
        slots[p] = static_cast<Slot>(s);
        found[s] = true;
      }
    }
    for (int s = kX; s <= kZ; ++s) {
      if (!found[s]) return FailHeader(element, "no property " + std::string(kNames[s]));
    }
    if ((found[kNx] || found[kNy] || found[kNz]) && !(found[kNx] && found[kNy] && found[kNz])) {
      return FailHeader(element, "normals need all of nx, ny and nz");
    }
    return slots;
  }

  Error FailHeader(const PlyElement& element, const std::string& message) const {
    return MakeError(std::string(source_) + ": header line " + std::to_string(element.line) + " (element " +
                     element.name + "): " + message);
  }

  Status ReadVertices(const PlyElement& element, PointCloud& cloud) {
    const Result<std::vector<Slot>> slots = VertexSlots(element);
    if (!slots.ok()) return slots.error();
    const bool has_intensity = std::find(slots->begin(), slots->end(), kIntensity) != slots->end();
    cloud.points.reserve(element.count);
    if (has_intensity) cloud.intensity.reserve(element.count);
    const bool has_normals = std::find(slots->begin(), slots->end(), kNx) != slots->end();
    if (has_normals) cloud.normals.reserve(element.count);
    std::string problem;
    for (std::uint64_t i = 0; i < element.count; ++i) {
      double values[kSkip + 1] = {};  // by Slot
      for (std::size_t p = 0; p < slots->size(); ++p) {
        double value = 0.0;
        const PlyProperty& property = element.properties[p];
        if (!ReadProperty(property, value, problem)) return Fail(element, i, property, problem);
        values[(*slots)[p]] = value;
      }
      cloud.points.emplace_back(static_cast<float>(values[kX]), static_cast<float>(values[kY]),
                                static_cast<float>(values[kZ]));
      if (has_intensity) cloud.intensity.push_back(static_cast<float>(values[kIntensity]));
      if (has_normals) {
        cloud.normals.emplace_back(static_cast<float>(values[kNx]), static_cast<float>(values[kNy]),
                                   static_cast<float>(values[kNz]));
      }
    }
    return Status::Ok();
  }

  // One cell per instance: its vertex_indices list holds no vertex (-1) or one.
  Status ReadGrid(const PlyElement& element, PointCloud& cloud) {
    std::string problem;
    cloud.grid.reserve(element.count);
    for (std::uint64_t i = 0; i < element.count; ++i) {
      std::int32_t cell = -1;
      for (const PlyProperty& property : element.properties) {
        if (property.name != "vertex_indices" || !property.list) {
          double ignored = 0.0;
          if (!ReadProperty(property, ignored, problem)) return Fail(element, i, property, problem);
          continue;
        }
        double count = 0.0;
        if (!cursor_.Next(property.count_type, count, problem)) return Fail(element, i, property, problem);
        if (count != 0.0 && count != 1.0) {
          return Fail(element, i, property, "lists " + FormatNumber(count) + " vertices; a grid cell holds 0 or 1");
        }
        if (count == 0.0) continue;
        double index = 0.0;
        if (!cursor_.Next(property.type, index, problem)) return Fail(element, i, property, problem);
        if (!IsIntegerIn(index, 0.0, static_cast<double>(kMaxPlyElements))) {
          return Fail(element, i, property, "bad vertex index " + FormatNumber(index));
        }
        cell = static_cast<std::int32_t>(index);
      }
      cloud.grid.push_back(cell);
    }
    return Status::Ok();
  }

  Status SkipElement(const PlyElement& element) {
    if (element.properties.empty()) return Status::Ok();  // nothing to read, however many
    std::string problem;
    for (std::uint64_t i = 0; i < element.count; ++i) {
      for (const PlyProperty& property : element.properties) {
        double ignored = 0.0;
        if (!ReadProperty(property, ignored, problem)) return Fail(element, i, property, problem);
      }
    }
    return Status::Ok();
  }

  Cursor& cursor_;
  std::string_view source_;
};

const PlyElement* FindElement(const PlyHeader& header, std::string_view name) {
  for (const PlyElement& element : header.elements) {
    if (element.name == name) return &element;
  }
  return nullptr;
}

// One vertex element, at most one range_grid, and the grid's shape from obj_info, all
// before any data is read.
Status CheckElements(const PlyHeader& header, std::string_view source) {
  std::size_t vertices = 0, grids = 0;
  for (const PlyElement& element : header.elements) {
    vertices += element.name == "vertex" ? 1 : 0;
    grids += element.name == "range_grid" ? 1 : 0;
  }
  if (vertices == 0) return MakeError(std::string(source) + ": no element vertex");
  if (vertices > 1) return MakeError(std::string(source) + ": " + std::to_string(vertices) + " vertex elements");
  if (grids > 1) return MakeError(std::string(source) + ": " + std::to_string(grids) + " range_grid elements");
  const PlyElement* grid = FindElement(header, "range_grid");
  if (grid == nullptr) return Status::Ok();
  const std::string where =
      std::string(source) + ": header line " + std::to_string(grid->line) + " (element range_grid): ";
  const auto is_indices = [](const PlyProperty& p) { return p.list && p.name == "vertex_indices"; };
  if (std::none_of(grid->properties.begin(), grid->properties.end(), is_indices)) {
    return MakeError(where + "no property list vertex_indices");
  }
  if (!header.num_cols || !header.num_rows) return MakeError(where + "no obj_info num_cols and num_rows");
  const std::uint64_t cells = *header.num_cols * *header.num_rows;
  if (grid->count != cells) {
    return MakeError(where + std::to_string(grid->count) + " cells, but obj_info num_cols " +
                     std::to_string(*header.num_cols) + " x num_rows " + std::to_string(*header.num_rows) +
                     " = " + std::to_string(cells));
  }
  return Status::Ok();
}

// Every cell's vertex must exist; runs after all elements, which may come in any order.
Status CheckGridIndices(const PlyHeader& header, std::string_view source, PointCloud& cloud) {
  if (FindElement(header, "range_grid") == nullptr) return Status::Ok();
  const auto cols = static_cast<std::size_t>(*header.num_cols);
  for (std::size_t i = 0; i < cloud.grid.size(); ++i) {
    if (cloud.grid[i] < 0 || static_cast<std::size_t>(cloud.grid[i]) < cloud.points.size()) continue;
    return MakeError(std::string(source) + ": range_grid cell " + std::to_string(i) + " (row " +
                     std::to_string(i / cols) + ", col " + std::to_string(i % cols) + "): vertex " +
                     std::to_string(cloud.grid[i]) + " out of range (" + std::to_string(cloud.points.size()) +
                     " vertices)");
  }
  cloud.grid_width = static_cast<int>(*header.num_cols);
  cloud.grid_height = static_cast<int>(*header.num_rows);
  return Status::Ok();
}

}  // namespace

Result<PointCloud> ParsePly(std::string_view bytes, std::string_view source_name) {
  const Result<PlyHeader> header = ParsePlyHeader(bytes, source_name);
  if (!header.ok()) return header.error();
  if (const Status elements = CheckElements(*header, source_name); !elements.ok()) return elements.error();
  const std::string_view data = bytes.substr(header->data_offset);
  PointCloud cloud;
  Status read = Status::Ok();
  if (header->format == PlyFormat::kAscii) {
    AsciiCursor cursor(data, header->data_line + 1);
    read = ElementReader<AsciiCursor>(cursor, source_name).Read(*header, cloud);
  } else {
    BinaryCursor cursor(data, header->data_offset, header->format == PlyFormat::kBinaryBigEndian);
    read = ElementReader<BinaryCursor>(cursor, source_name).Read(*header, cloud);
  }
  if (!read.ok()) return read.error();
  if (const Status grid = CheckGridIndices(*header, source_name, cloud); !grid.ok()) return grid.error();
  return cloud;
}

Result<PointCloud> ReadPly(const std::filesystem::path& path) {
  const Result<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.error();
  return ParsePly(*bytes, path.string());
}

}  // namespace flat2d::hal::cloud
