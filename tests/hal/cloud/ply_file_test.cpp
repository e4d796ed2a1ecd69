// PLY files built inline: ASCII and binary of both byte orders, skipped properties, lists
// and elements, Stanford-style range grids, and malformed files whose errors must name the
// file and the line, element and property.
#include "hal/cloud/ply_file.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

namespace flat2d::hal::cloud {
namespace {

// Appends `value` in little- or big-endian byte order.
template <typename T>
void Append(std::string& bytes, T value, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  bytes.append(raw, sizeof(T));
}

std::string PlyErrorOf(const std::string& bytes) {
  const Result<PointCloud> cloud = ParsePly(bytes, "x.ply");
  return cloud.ok() ? std::string("(no error)") : cloud.error().message;
}

// Three vertices, a face, and a 3 x 2 range grid; line 17 is the first data line.
const std::string kAsciiHeader =
    "ply\n"
    "format ascii 1.0\n"
    "comment made by hand\n"
    "obj_info num_cols 3\n"
    "obj_info num_rows 2\n"
    "element vertex 3\n"
    "property float x\n"
    "property float32 y\n"
    "property double z\n"
    "property uchar intensity\n"
    "property list uchar int extra\n"
    "element face 1\n"
    "property list uint8 int32 vertex_indices\n"
    "element range_grid 6\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";
const std::string kAsciiVertices = "0.5 -1 2.25 200 2 7 8\n1 2 3 4 0\n-0.5 0 1e-3 0 1 5\n";
const std::string kAsciiFace = "3 0 1 2\n";

TEST(PlyFile, AsciiVerticesAndRangeGrid) {
  const std::string file = kAsciiHeader + kAsciiVertices + kAsciiFace + "0\n1 0\n1 2\n0\n1 1\n0\n";
  const Result<PointCloud> cloud = ParsePly(file, "x.ply");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 3u);
  EXPECT_EQ(cloud->points[0], Eigen::Vector3f(0.5f, -1.0f, 2.25f));
  EXPECT_EQ(cloud->points[2], Eigen::Vector3f(-0.5f, 0.0f, 0.001f));
  EXPECT_EQ(cloud->intensity, (std::vector<float>{200, 4, 0}));
  EXPECT_EQ(cloud->grid_width, 3);
  EXPECT_EQ(cloud->grid_height, 2);
  EXPECT_EQ(cloud->grid, (std::vector<std::int32_t>{-1, 0, 2, -1, 1, -1}));
}

// The same kind of content in binary: vertex x y z confidence intensity, a face list.
std::string BinaryPly(bool big_endian) {
  std::string file = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                     "property float confidence\nproperty int16 intensity\nelement face 1\n"
                     "property list uchar uint vertex_indices\nend_header\n";
  for (int i = 0; i < 2; ++i) {
    Append(file, 1.25f + static_cast<float>(i), big_endian);
    Append(file, -3.5f, big_endian);
    Append(file, 1e-3f * static_cast<float>(i), big_endian);
    Append(file, 0.75f, big_endian);
    Append(file, static_cast<std::int16_t>(-2 + 300 * i), big_endian);
  }
  Append(file, static_cast<std::uint8_t>(3), big_endian);
  for (std::uint32_t v : {0u, 1u, 1u}) Append(file, v, big_endian);
  return file;
}

TEST(PlyFile, BinaryOfBothByteOrders) {
  for (const bool big_endian : {false, true}) {
    const Result<PointCloud> cloud = ParsePly(BinaryPly(big_endian), "x.ply");
    ASSERT_TRUE(cloud.ok()) << cloud.error().message;
    ASSERT_EQ(cloud->points.size(), 2u);
    EXPECT_EQ(cloud->points[0], Eigen::Vector3f(1.25f, -3.5f, 0.0f)) << big_endian;
    EXPECT_EQ(cloud->points[1], Eigen::Vector3f(2.25f, -3.5f, 1e-3f)) << big_endian;
    EXPECT_EQ(cloud->intensity, (std::vector<float>{-2, 298})) << big_endian;
    EXPECT_FALSE(cloud->organized());
  }
}

// Normals as MeshLab, CloudCompare and flat2d's own writer store them: nx ny nz after x y z.
TEST(PlyFile, NormalsAreKeptWhenAllThreeArePresent) {
  const Result<PointCloud> cloud = ParsePly(
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nend_header\n1 2 3 0 0 1\n4 5 6 0.6 -0.8 0\n",
      "n.ply");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->normals.size(), 2U);
  EXPECT_EQ(cloud->normals[0], Eigen::Vector3f(0.0F, 0.0F, 1.0F));
  EXPECT_EQ(cloud->normals[1], Eigen::Vector3f(0.6F, -0.8F, 0.0F));
  EXPECT_EQ(PlyErrorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                       "property float nx\nproperty float ny\nend_header\n1 2 3 0 1\n"),
            "x.ply: header line 3 (element vertex): normals need all of nx, ny and nz");
  const Result<PointCloud> plain = ParsePly(kAsciiHeader + kAsciiVertices + kAsciiFace + "0\n1 0\n1 1\n1 2\n0\n0\n", "p.ply");
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_TRUE(plain->normals.empty());
}

TEST(PlyFile, HeaderErrorsNameTheLineAndProperty) {
  EXPECT_EQ(PlyErrorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty flaot x\n"),
            "x.ply: header line 4 (property x): unknown type 'flaot'");
  EXPECT_EQ(PlyErrorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\n"
                       "end_header\n1 2\n"),
            "x.ply: header line 3 (element vertex): no property x");
  EXPECT_EQ(PlyErrorOf("ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\n"),
            "x.ply: header line 4 (property vertex_indices): list count type 'float' is no integer type");
  EXPECT_EQ(PlyErrorOf("ply\nformat binary_middle_endian 1.0\n"),
            "x.ply: header line 2: unknown format 'binary_middle_endian'");
  EXPECT_EQ(PlyErrorOf("PLY\n"), "x.ply: not a PLY file (no 'ply' line)");
  EXPECT_EQ(PlyErrorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"),
            "x.ply: header: no end_header line");
  EXPECT_EQ(PlyErrorOf("ply\nformat ascii 1.0\nelement face 0\nend_header\n"), "x.ply: no element vertex");
}

TEST(PlyFile, DataErrorsNameTheElementAndProperty) {
  EXPECT_EQ(PlyErrorOf(kAsciiHeader + "0.5 -1 2.25 200 2 7 8\n1 2"),
            "x.ply: line 18 (vertex 1, property z): data ends");
  EXPECT_EQ(PlyErrorOf(kAsciiHeader + "0.5 -1 2.25 200 2 7 8\n1 two 3 4 0\n"),
            "x.ply: line 18 (vertex 1, property y): bad number 'two'");
  EXPECT_EQ(PlyErrorOf(kAsciiHeader + "0.5 -1 2.25 200 -2 7 8\n"),
            "x.ply: line 17 (vertex 0, property extra): bad list count -2");
  const std::string binary = BinaryPly(false);
  const std::size_t data_start = binary.find("end_header\n") + 11;
  EXPECT_EQ(PlyErrorOf(binary.substr(0, data_start + 18 + 8)), "x.ply: byte " + std::to_string(data_start + 26) +
                                                                    " (vertex 1, property z): data ends");
  EXPECT_EQ(PlyErrorOf(binary.substr(0, binary.size() - 2)),
            "x.ply: byte " + std::to_string(data_start + 36 + 1) + " (face 0, property vertex_indices): data ends");
  std::string huge = binary;
  huge.replace(huge.find("vertex 2"), 8, "vertex 9");
  EXPECT_EQ(PlyErrorOf(huge.substr(0, data_start + 18)),
            "x.ply: header line 3 (element vertex): 9 instances cannot fit in the 18 bytes left");
}

TEST(PlyFile, RangeGridErrors) {
  const std::string body = kAsciiVertices + kAsciiFace;
  std::string wrong_count = kAsciiHeader;
  wrong_count.replace(wrong_count.find("range_grid 6"), 12, "range_grid 5");
  EXPECT_EQ(PlyErrorOf(wrong_count + body),
            "x.ply: header line 14 (element range_grid): 5 cells, but obj_info num_cols 3 x num_rows 2 = 6");
  std::string no_shape = kAsciiHeader;
  no_shape.erase(no_shape.find("obj_info num_rows 2\n"), 20);
  EXPECT_EQ(PlyErrorOf(no_shape + body),
            "x.ply: header line 13 (element range_grid): no obj_info num_cols and num_rows");
  EXPECT_EQ(PlyErrorOf(kAsciiHeader + body + "0\n1 0\n1 2\n0\n1 3\n0\n"),
            "x.ply: range_grid cell 4 (row 1, col 1): vertex 3 out of range (3 vertices)");
  EXPECT_EQ(PlyErrorOf(kAsciiHeader + body + "0\n1 0\n2 1 2\n"),
            "x.ply: line 23 (range_grid 2, property vertex_indices): lists 2 vertices; a grid cell holds 0 or 1");
  EXPECT_EQ(PlyErrorOf(kAsciiHeader + body + "0\n1 0\n1 -2\n"),
            "x.ply: line 23 (range_grid 2, property vertex_indices): bad vertex index -2");
  EXPECT_EQ(ReadPly("/nonexistent/x.ply").error().message, "/nonexistent/x.ply: cannot open");
}

}  // namespace
}  // namespace flat2d::hal::cloud
