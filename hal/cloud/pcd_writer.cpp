#include "hal/cloud/pcd_writer.hpp"

#include <bit>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace flat2d::hal::cloud {
namespace {

static_assert(std::endian::native == std::endian::little, "PCD binary records are written as memory holds them");

// One field of a record: its name, bytes and PCD type letter, and where its value is.
struct PcdField {
  const char* name;
  std::size_t size;
  char type;
  const void* values;  // `size` bytes per point
};

std::vector<PcdField> FieldsOf(const PointCloud& cloud) {
  std::vector<PcdField> fields{{"x", 4, 'F', nullptr}, {"y", 4, 'F', nullptr}, {"z", 4, 'F', nullptr}};
  if (!cloud.intensity.empty()) fields.push_back({"intensity", 4, 'F', cloud.intensity.data()});
  if (!cloud.ring.empty()) fields.push_back({"ring", 2, 'U', cloud.ring.data()});
  return fields;
}

Status CheckPcdChannel(const std::filesystem::path& path, const char* name, std::size_t size, std::size_t points) {
  if (size == 0 || size == points) return Status::Ok();
  return MakeError(path.string() + ": " + std::to_string(size) + " " + name + " values for " + std::to_string(points) +
                   " points");
}

std::string PcdHeaderText(const std::vector<PcdField>& fields, std::size_t points) {
  std::string names, sizes, types, counts;
  for (const PcdField& f : fields) {
    names.append(" ").append(f.name);
    sizes.append(" ").append(std::to_string(f.size));
    types.append(" ").push_back(f.type);
    counts.append(" 1");
  }
  const std::string n = std::to_string(points);
  std::string header("# .PCD v0.7 - Point Cloud Data file format (flat2d)\nVERSION 0.7\n");
  header.append("FIELDS").append(names).append("\nSIZE").append(sizes).append("\nTYPE").append(types);
  header.append("\nCOUNT").append(counts).append("\nWIDTH ").append(n).append("\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0");
  header.append("\nPOINTS ").append(n).append("\nDATA binary\n");
  return header;
}

// The records, packed (no padding between a 4-byte float and a 2-byte ring).
std::vector<char> PcdRecords(const PointCloud& cloud, const std::vector<PcdField>& fields) {
  std::size_t record = 0;
  for (const PcdField& f : fields) record += f.size;
  std::vector<char> bytes(record * cloud.points.size());
  char* out = bytes.data();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    std::memcpy(out, cloud.points[i].data(), 12);  // x y z
    out += 12;
    for (std::size_t k = 3; k < fields.size(); ++k) {
      std::memcpy(out, static_cast<const char*>(fields[k].values) + i * fields[k].size, fields[k].size);
      out += fields[k].size;
    }
  }
  return bytes;
}

}  // namespace

Status WritePcd(const std::filesystem::path& path, const PointCloud& cloud) {
  const std::size_t points = cloud.points.size();
  if (Status s = CheckPcdChannel(path, "intensity", cloud.intensity.size(), points); !s.ok()) return s;
  if (Status s = CheckPcdChannel(path, "ring", cloud.ring.size(), points); !s.ok()) return s;
  const std::vector<PcdField> fields = FieldsOf(cloud);
  std::ofstream file(path, std::ios::binary);
  if (!file) return MakeError(path.string() + ": cannot open for writing");
  const std::string header = PcdHeaderText(fields, points);
  const std::vector<char> records = PcdRecords(cloud, fields);
  file.write(header.data(), static_cast<std::streamsize>(header.size()));
  file.write(records.data(), static_cast<std::streamsize>(records.size()));
  file.close();
  if (!file) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

}  // namespace flat2d::hal::cloud
