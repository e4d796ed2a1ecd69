// PLY files written whole and streamed, read back by ReadPly: points and normals as given
// (moved by the streamed pose), the patched vertex count, and the errors.
#include "hal/cloud/ply_writer.hpp"

#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "hal/cloud/ply_file.hpp"

namespace flat2d::hal::cloud {
namespace {

std::filesystem::path TempPly(const std::string& name) { return std::filesystem::path(::testing::TempDir()) / name; }

TEST(PlyWriter, WholeCloudReadsBackWithNormals) {
  const std::vector<Eigen::Vector3f> points{{1.5f, -2.0f, 0.25f}, {3.0f, 4.0f, -5.0f}};
  const std::vector<Eigen::Vector3f> normals{{0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}};
  const auto path = TempPly("whole.ply");
  ASSERT_TRUE(WritePly(path, points, normals).ok());
  const Result<PointCloud> cloud = ReadPly(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  EXPECT_EQ(cloud->points, points);
  EXPECT_EQ(cloud->normals, normals);
  ASSERT_TRUE(WritePly(path, points, {}).ok());
  EXPECT_TRUE(ReadPly(path)->normals.empty());
}

TEST(PlyWriter, StreamedBatchesAreMovedAndCounted) {
  const auto path = TempPly("streamed.ply");
  auto writer = PlyStreamWriter::Open(path, true);
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  Eigen::Isometry3f pose(Eigen::AngleAxisf(0.5f * static_cast<float>(M_PI), Eigen::Vector3f::UnitZ()));
  pose.translation() = Eigen::Vector3f(10.0f, 0.0f, 1.0f);
  ASSERT_TRUE(writer->Append({{1.0f, 0.0f, 0.0f}}, {{1.0f, 0.0f, 0.0f}}).ok());
  ASSERT_TRUE(writer->Append({{1.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}}, {{1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}},
                             pose.matrix()).ok());
  EXPECT_EQ(writer->points(), 3u);
  ASSERT_TRUE(writer->Close().ok());
  const Result<PointCloud> cloud = ReadPly(path);
  ASSERT_TRUE(cloud.ok()) << cloud.error().message;
  ASSERT_EQ(cloud->points.size(), 3u);
  EXPECT_TRUE(cloud->points[1].isApprox(Eigen::Vector3f(10.0f, 1.0f, 1.0f), 1e-6f)) << cloud->points[1].transpose();
  EXPECT_TRUE(cloud->points[2].isApprox(Eigen::Vector3f(8.0f, 0.0f, 1.0f), 1e-6f)) << cloud->points[2].transpose();
  EXPECT_TRUE(cloud->normals[1].isApprox(Eigen::Vector3f(0.0f, 1.0f, 0.0f), 1e-6f));  // turned, not moved
  EXPECT_TRUE(cloud->normals[2].isApprox(Eigen::Vector3f(0.0f, 0.0f, 1.0f), 1e-6f));
}

TEST(PlyWriter, MismatchedNormalsAndUnwritablePathsAreErrorsNamingTheFile) {
  EXPECT_EQ(WritePly("/nonexistent/dir/x.ply", {{0, 0, 0}}, {}).error().message,
            "/nonexistent/dir/x.ply: cannot open for writing");
  EXPECT_EQ(WritePly(TempPly("bad.ply"), {{0, 0, 0}, {1, 1, 1}}, {{0, 0, 1}}).error().message,
            TempPly("bad.ply").string() + ": 1 normals for 2 points");
  auto writer = PlyStreamWriter::Open(TempPly("plain.ply"), false);
  ASSERT_TRUE(writer.ok());
  EXPECT_EQ(writer->Append({{0, 0, 0}}, {{0, 0, 1}}).error().message,
            TempPly("plain.ply").string() + ": 1 normals for 1 points (opened without normals)");
  ASSERT_TRUE(writer->Close().ok());
  EXPECT_FALSE(writer->Close().ok());
  EXPECT_EQ(ReadPly(TempPly("plain.ply"))->points.size(), 0u);  // the rejected batch wrote nothing
}

}  // namespace
}  // namespace flat2d::hal::cloud
