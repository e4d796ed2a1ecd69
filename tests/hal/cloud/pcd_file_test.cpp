// PCD files built inline: ascii, binary and binary_compressed data, skipped fields,
// organized clouds, and malformed files whose errors must name the file and the field
// or header line.
#include "hal/cloud/pcd_file.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "tests/hal/cloud/lzf_golden.hpp"

namespace flat2d::hal::cloud {
namespace {

// Appends the bytes of `value` as the host (little-endian) stores it.
template <typename T>
void Append(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

std::string Header(const std::string& fields, const std::string& sizes, const std::string& types,
                   const std::string& dims, const std::string& data) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes +
         "\nTYPE " + types + "\n" + dims + "VIEWPOINT 0 0 0 1 0 0 0\nDATA " + data + "\n";
}

std::string Dims(int width, int height, int points) {
  return "WIDTH " + std::to_string(width) + "\nHEIGHT " + std::to_string(height) + "\nPOINTS " +
         std::to_string(points) + "\n";
}

std::string PcdErrorOf(const std::string& bytes) {
  const Result<PointCloud> cloud = ParsePcd(bytes, "x.pcd");
  return cloud.ok() ? std::string("(no error)") : cloud.error().message;
}

TEST(PcdFile, AsciiKeepsIntensityAndRing) {
  const std::string file = Header("x y z intensity ring", "4 4 4 1 2", "F F F U U", Dims(3, 1, 3), "ascii") +
                           "1.5 -2 0.25 17 3\n\n-0.125 4e2 -7.5 255 0\r\n0 0 0 0 15\n";
  const Result<PointCloud> cloud = ParsePcd(file, "x.pcd");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 3u);
  EXPECT_EQ(cloud->points[0], Eigen::Vector3f(1.5f, -2.0f, 0.25f));
  EXPECT_EQ(cloud->points[1], Eigen::Vector3f(-0.125f, 400.0f, -7.5f));
  EXPECT_EQ(cloud->intensity, (std::vector<float>{17.0f, 255.0f, 0.0f}));
  EXPECT_EQ(cloud->ring, (std::vector<std::uint16_t>{3, 0, 15}));
  EXPECT_FALSE(cloud->organized());
  EXPECT_TRUE(cloud->grid.empty());
}

TEST(PcdFile, BinarySkipsOtherFieldsByTheirSizeTimesCount) {
  // x y z as doubles, a 3-float normal between them and intensity (int16), a double after.
  std::string file = Header("x y normal z intensity t", "8 8 4 8 2 8", "F F F F I F", "COUNT 1 1 3 1 1 1\n" +
                            Dims(2, 1, 2), "binary");
  for (int i = 0; i < 2; ++i) {
    Append(file, 10.0 + i);
    Append(file, -20.5 - i);
    for (int k = 0; k < 3; ++k) Append(file, 99.0f);
    Append(file, 0.125 * (i + 1));
    Append(file, static_cast<std::int16_t>(-300 + i));
    Append(file, 1.0e9);
  }
  const Result<PointCloud> cloud = ParsePcd(file, "x.pcd");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 2u);
  EXPECT_EQ(cloud->points[0], Eigen::Vector3f(10.0f, -20.5f, 0.125f));
  EXPECT_EQ(cloud->points[1], Eigen::Vector3f(11.0f, -21.5f, 0.25f));
  EXPECT_EQ(cloud->intensity, (std::vector<float>{-300.0f, -299.0f}));
  EXPECT_TRUE(cloud->ring.empty());
}

TEST(PcdFile, BinaryCompressedDecodesLiblzfColumns) {
  std::string file = Header("x y z intensity ring", "4 4 4 1 2", "F F F U U", Dims(6, 1, 6), "binary_compressed");
  Append(file, static_cast<std::uint32_t>(kGoldenLzf.size()));
  Append(file, static_cast<std::uint32_t>(kGoldenUncompressedBytes));
  file += kGoldenLzf;
  const Result<PointCloud> cloud = ParsePcd(file, "x.pcd");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  const GoldenColumns expected;
  ASSERT_EQ(cloud->points.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(cloud->points[i], Eigen::Vector3f(expected.x[i], expected.y[i], expected.z[i])) << i;
    EXPECT_EQ(cloud->intensity[i], static_cast<float>(expected.intensity[i])) << i;
    EXPECT_EQ(cloud->ring[i], expected.ring[i]) << i;
  }
}

TEST(PcdFile, OrganizedCloudGridIsTheIdentityWithNanHoles) {
  const std::string file = Header("x y z", "4 4 4", "F F F", Dims(2, 2, 4), "ascii") +
                           "1 2 3\n4 5 6\nnan nan nan\n7 8 9\n";
  const Result<PointCloud> cloud = ParsePcd(file, "x.pcd");
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  EXPECT_TRUE(cloud->organized());
  EXPECT_EQ(cloud->grid_width, 2);
  EXPECT_EQ(cloud->grid_height, 2);
  EXPECT_EQ(cloud->grid, (std::vector<std::int32_t>{0, 1, -1, 3}));
  EXPECT_TRUE(std::isnan(cloud->points[2].x()));
  EXPECT_EQ(cloud->points[3], Eigen::Vector3f(7, 8, 9));
}

TEST(PcdFile, OldHeadersAreUnorganizedClouds) {
  // WIDTH 0 HEIGHT 0 as tier4's Nebula writes it, and a v0.6 header with neither.
  const std::string zero = Header("x y z", "4 4 4", "F F F", "WIDTH 0\nHEIGHT 0\nPOINTS 2\n", "ascii") +
                           "1 2 3\n4 5 6\n";
  const std::string none = "VERSION .6\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n";
  const std::pair<std::string, Eigen::Vector3f> cases[] = {{zero, {4, 5, 6}}, {none, {1, 2, 3}}};
  for (const auto& [file, last] : cases) {
    const Result<PointCloud> cloud = ParsePcd(file, "x.pcd");
    ASSERT_TRUE(cloud.ok()) << cloud.error().message;
    EXPECT_FALSE(cloud->organized());
    EXPECT_EQ(cloud->points.back(), last);
  }
}

TEST(PcdFile, HeaderErrorsNameTheLineAndField) {
  EXPECT_EQ(PcdErrorOf(Header("x y z intensity", "4 4 4", "F F F F", Dims(1, 1, 1), "ascii")),
            "x.pcd: header line 4 (SIZE): 3 entries for 4 FIELDS");
  EXPECT_EQ(PcdErrorOf(Header("y z", "4 4", "F F", Dims(1, 1, 1), "ascii") + "1 2\n"), "x.pcd: FIELDS has no x");
  EXPECT_EQ(PcdErrorOf(Header("x y z", "4 4 4", "F F Q", Dims(1, 1, 1), "ascii")),
            "x.pcd: header line 5 (TYPE): field z: unknown type 'Q'");
  EXPECT_EQ(PcdErrorOf(Header("x y z", "2 4 4", "F F F", Dims(1, 1, 1), "ascii")),
            "x.pcd: header line 5 (TYPE): field x: F with SIZE 2 is no numeric type");
  EXPECT_EQ(PcdErrorOf(Header("x y z", "4 4 4", "U F F", Dims(1, 1, 1), "ascii")),
            "x.pcd: field x: expected TYPE F (SIZE 4 or 8)");
  EXPECT_EQ(PcdErrorOf(Header("x y z ring", "4 4 4 4", "F F F F", Dims(1, 1, 1), "ascii")),
            "x.pcd: field ring: TYPE F, expected an integer type (I or U)");
  EXPECT_EQ(PcdErrorOf(Header("x y z", "4 4 4", "F F F", Dims(2, 2, 5), "ascii")),
            "x.pcd: header line 8 (POINTS): 5 points, but WIDTH 2 x HEIGHT 2 = 4");
  EXPECT_EQ(PcdErrorOf(Header("x y z", "4 4 4", "F F F", Dims(1, 1, 1), "binary_zstd")),
            "x.pcd: header line 10 (DATA): unknown data kind 'binary_zstd'");
  EXPECT_EQ(PcdErrorOf("VERSION 0.7\nFIELDS x y z\nSIZES 4 4 4\n"), "x.pcd: header line 3 (SIZES): unknown keyword");
  EXPECT_EQ(PcdErrorOf("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\n"), "x.pcd: header: no DATA line");
  EXPECT_EQ(PcdErrorOf("VERSION 0.7\nFIELDS x y z\nTYPE F F F\nPOINTS 1\nDATA ascii\n"), "x.pcd: header: no SIZE line");
}

TEST(PcdFile, DataErrorsNameTheFileAndField) {
  const std::string xyz = Header("x y z", "4 4 4", "F F F", Dims(2, 1, 2), "binary");
  EXPECT_EQ(PcdErrorOf(xyz + std::string(20, '\0')), "x.pcd: DATA binary: 20 bytes for 2 points of 12 bytes");
  const std::string ascii = Header("x y z", "4 4 4", "F F F", Dims(2, 1, 2), "ascii");
  EXPECT_EQ(PcdErrorOf(ascii + "1 2 3\n"), "x.pcd: DATA ascii: 1 point lines, POINTS says 2");
  EXPECT_EQ(PcdErrorOf(ascii + "1 2 3\n4 abc 6\n"), "x.pcd: line 12 (field y): bad number 'abc'");
  EXPECT_EQ(PcdErrorOf(ascii + "1 2 3 4\n"), "x.pcd: line 11: 4 values, FIELDS and COUNT say 3");
  std::string ring = Header("x y z ring", "4 4 4 2", "F F F I", Dims(1, 1, 1), "binary");
  for (int i = 0; i < 3; ++i) Append(ring, 1.0f);
  Append(ring, static_cast<std::int16_t>(-1));
  EXPECT_EQ(PcdErrorOf(ring), "x.pcd: point 0: ring -1 is not in 0..65535");
}

TEST(PcdFile, CompressedErrorsNameTheSizes) {
  const std::string header = Header("x y z intensity ring", "4 4 4 1 2", "F F F U U", Dims(6, 1, 6),
                                    "binary_compressed");
  const auto file = [&](std::uint32_t compressed, std::uint32_t uncompressed, std::string_view payload) {
    std::string bytes = header;
    Append(bytes, compressed);
    Append(bytes, uncompressed);
    return bytes + std::string(payload);
  };
  const std::string where = "x.pcd: DATA binary_compressed: ";
  EXPECT_EQ(PcdErrorOf(header + "\x01\x02"), where + "no compressed and uncompressed sizes");
  EXPECT_EQ(PcdErrorOf(file(50, 90, kGoldenLzf)), where + "compressed size 50, but 49 bytes follow");
  EXPECT_EQ(PcdErrorOf(file(49, 91, kGoldenLzf)), where + "uncompressed size 91, but POINTS x record = 90");
  EXPECT_EQ(PcdErrorOf(file(1, 90, std::string_view("\0", 1))), where + "1 bytes cannot expand to 90");
  EXPECT_EQ(PcdErrorOf(file(48, 90, kGoldenLzf.substr(0, 48))), where + "malformed LZF data");
  EXPECT_EQ(ReadPcd("/nonexistent/x.pcd").error().message, "/nonexistent/x.pcd: cannot open");
}

}  // namespace
}  // namespace flat2d::hal::cloud
