#include "hal/cloud/pcd_writer.hpp"

#include <bit>
#include <cstring>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace flat2d::hal::cloud {
namespace {

static_assert(std::endian::native == std::endian::little, "PCD binary records are written as memory holds them");

struct PcdFileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

Status CheckPcdChannel(const std::filesystem::path& path, const char* name, std::size_t size, std::size_t points) {
  if (size == 0 || size == points) return Status::Ok();
  return MakeError(path.string() + ": " + std::to_string(size) + " " + name + " values for " + std::to_string(points) +
                   " points");
}

std::string PcdHeaderText(const PointCloud& cloud) {
  const bool intensity = !cloud.intensity.empty(), ring = !cloud.ring.empty();
  const std::string n = std::to_string(cloud.points.size());
  return std::string("# .PCD v0.7 - Point Cloud Data file format (flat2d)\nVERSION 0.7\n") +
         "FIELDS x y z" + (intensity ? " intensity" : "") + (ring ? " ring" : "") + "\n" +
         "SIZE 4 4 4" + (intensity ? " 4" : "") + (ring ? " 2" : "") + "\n" +
         "TYPE F F F" + (intensity ? " F" : "") + (ring ? " U" : "") + "\n" +
         "COUNT 1 1 1" + (intensity ? " 1" : "") + (ring ? " 1" : "") + "\n" +
         "WIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA binary\n";
}

// The records, packed (no padding between a 4-byte float and a 2-byte ring).
std::vector<unsigned char> PcdRecords(const PointCloud& cloud) {
  const bool intensity = !cloud.intensity.empty(), ring = !cloud.ring.empty();
  const std::size_t record = 12 + (intensity ? 4 : 0) + (ring ? 2 : 0);
  std::vector<unsigned char> bytes(record * cloud.points.size());
  unsigned char* out = bytes.data();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    std::memcpy(out, cloud.points[i].data(), 12);
    out += 12;
    if (intensity) {
      std::memcpy(out, &cloud.intensity[i], 4);
      out += 4;
    }
    if (ring) {
      std::memcpy(out, &cloud.ring[i], 2);
      out += 2;
    }
  }
  return bytes;
}

}  // namespace

Status WritePcd(const std::filesystem::path& path, const PointCloud& cloud) {
  const std::size_t points = cloud.points.size();
  if (Status s = CheckPcdChannel(path, "intensity", cloud.intensity.size(), points); !s.ok()) return s;
  if (Status s = CheckPcdChannel(path, "ring", cloud.ring.size(), points); !s.ok()) return s;
  std::unique_ptr<std::FILE, PcdFileCloser> file(std::fopen(path.c_str(), "wb"));
  if (file == nullptr) return MakeError(path.string() + ": cannot open for writing");
  const std::string header = PcdHeaderText(cloud);
  const std::vector<unsigned char> records = PcdRecords(cloud);
  const bool written = std::fwrite(header.data(), 1, header.size(), file.get()) == header.size() &&
                       std::fwrite(records.data(), 1, records.size(), file.get()) == records.size();
  if (std::fclose(file.release()) != 0 || !written) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

}  // namespace flat2d::hal::cloud
