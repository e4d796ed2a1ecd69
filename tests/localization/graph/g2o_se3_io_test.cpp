// g2o's 3D records: a round trip keeps ids, poses, information and FIX; malformed lines fail
// naming the source and the line (missing fields, non-numbers, a quaternion that is not a
// rotation, an edge to an unknown vertex, 2D records mixed in, information without SE-Sync
// weights); quaternions off unit norm by rounding are normalized; the file front door tells
// 3D from 2D g2o.
#include "localization/graph/g2o_se3_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "localization/graph/graph_file.hpp"

namespace flat2d::localization::graph {
namespace {

constexpr const char* kUnitInformation = "1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1";

// Vertex 7 turned 90 degrees about z; the first edge's information has every entry distinct.
constexpr const char* kG2oSe3 = R"(# a comment
VERTEX_SE3:QUAT 3 0 0 0 0 0 0 1
VERTEX_SE3:QUAT 7 1.5 -2 0.25 0 0 0.7071067811865476 0.7071067811865476
VERTEX_SE3:QUAT 5 1 0 0 0 0 0 1

EDGE_SE3:QUAT 3 5 1 0 0 0 0 0 1 11 1 2 3 4 5 12 6 7 8 9 13 10 11 12 400 13 14 401 15 402
EDGE_SE3:QUAT 5 7 0.5 -2 0.25 0 0 0.7071067811865476 0.7071067811865476 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1
FIX 3
)";

Se3PoseGraph ReadText(const std::string& text) {
  std::istringstream in(text);
  Result<Se3PoseGraph> graph = ReadG2oSe3(in, "test.g2o");
  EXPECT_TRUE(graph.ok()) << graph.error().message;
  return graph.ok() ? std::move(graph).value() : Se3PoseGraph{};
}

std::string ErrorOf(const std::string& text) {
  std::istringstream in(text);
  const Result<Se3PoseGraph> graph = ReadG2oSe3(in, "bad.g2o");
  EXPECT_FALSE(graph.ok()) << text;
  return graph.ok() ? std::string() : graph.error().message;
}

std::string Edge(int from, int to, const std::string& pose = "1 0 0 0 0 0 1") {
  return "EDGE_SE3:QUAT " + std::to_string(from) + " " + std::to_string(to) + " " + pose + " " +
         kUnitInformation + "\n";
}

TEST(G2oSe3IoTest, ReadsVerticesEdgesInformationAndFix) {
  const Se3PoseGraph graph = ReadText(kG2oSe3);
  ASSERT_EQ(graph.nodes.size(), 3u);
  EXPECT_EQ(graph.nodes[1].id, 5);  // sorted by id
  EXPECT_EQ(graph.nodes[2].id, 7);
  EXPECT_TRUE(graph.nodes[0].fixed);
  EXPECT_FALSE(graph.nodes[2].fixed);
  EXPECT_TRUE(graph.nodes[2].estimate.translation().isApprox(Eigen::Vector3d(1.5, -2.0, 0.25)));
  EXPECT_TRUE(graph.nodes[2].estimate.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
  ASSERT_EQ(graph.betweens.size(), 2u);
  EXPECT_EQ(graph.betweens[1].from, 1u);
  EXPECT_EQ(graph.betweens[1].to, 2u);
  const Matrix6d& l = graph.betweens[0].information;
  EXPECT_EQ(l(0, 0), 11.0);
  EXPECT_EQ(l(0, 5), 5.0);
  EXPECT_EQ(l(5, 0), 5.0);  // the upper triangle mirrored
  EXPECT_EQ(l(1, 2), 6.0);
  EXPECT_EQ(l(3, 5), 14.0);
  EXPECT_EQ(l(5, 5), 402.0);
}

TEST(G2oSe3IoTest, RoundTripKeepsEverything) {
  const Se3PoseGraph graph = ReadText(kG2oSe3);
  std::ostringstream out;
  ASSERT_TRUE(WriteG2oSe3(graph, out).ok());
  const Se3PoseGraph again = ReadText(out.str());
  ASSERT_EQ(again.nodes.size(), graph.nodes.size());
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    EXPECT_EQ(again.nodes[n].id, graph.nodes[n].id);
    EXPECT_EQ(again.nodes[n].fixed, graph.nodes[n].fixed);
    EXPECT_TRUE(again.nodes[n].estimate.isApprox(graph.nodes[n].estimate, 1e-15));
  }
  ASSERT_EQ(again.betweens.size(), graph.betweens.size());
  for (std::size_t e = 0; e < graph.betweens.size(); ++e) {
    EXPECT_EQ(again.betweens[e].from, graph.betweens[e].from);
    EXPECT_EQ(again.betweens[e].to, graph.betweens[e].to);
    EXPECT_TRUE(again.betweens[e].measurement.isApprox(graph.betweens[e].measurement, 1e-15));
    EXPECT_EQ(again.betweens[e].information, graph.betweens[e].information);
  }
}

TEST(G2oSe3IoTest, QuaternionsOffByRoundingAreNormalized) {
  // Norm 1.0004 (files print 6-7 digits) is read and normalized; 1.5 is not a rotation.
  const Se3PoseGraph graph = ReadText("VERTEX_SE3:QUAT 0 0 0 0 0 0 0.6 0.8003\n");
  const Eigen::Matrix3d r = graph.nodes[0].estimate.linear();
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-14);
  EXPECT_EQ(ErrorOf("VERTEX_SE3:QUAT 0 0 0 0 0 0 0.9 1.2\n"),
            "bad.g2o:1: quaternion norm 1.500000 is not 1: not a rotation");
  EXPECT_EQ(ErrorOf("VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n" + Edge(0, 1, "1 0 0 0 0 0 0")),
            "bad.g2o:2: quaternion norm 0.000000 is not 1: not a rotation");
}

TEST(G2oSe3IoTest, MalformedLinesNameTheFileAndLine) {
  const std::string v0 = "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n";
  const std::string v1 = "VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n";
  EXPECT_EQ(ErrorOf(v0 + "VERTEX_SE3:QUAT 1 0 0 0 0 0 1\n"),
            "bad.g2o:2: VERTEX_SE3:QUAT needs 7 numbers after its ids, found 6");
  EXPECT_EQ(ErrorOf(v0 + v1 + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0\n"),
            "bad.g2o:3: EDGE_SE3:QUAT needs 28 numbers after its ids, found 10");
  EXPECT_EQ(ErrorOf("\n\nVERTEX_SE3:QUAT 0 0 0 zero 0 0 0 1\n"),
            "bad.g2o:3: field 5 'zero' is not a finite number");
  EXPECT_EQ(ErrorOf("VERTEX_SE3:QUAT 0 0 0 0 0 0 0 inf\n"),
            "bad.g2o:1: field 9 'inf' is not a finite number");
  EXPECT_EQ(ErrorOf("VERTEX_SE3:QUAT x 0 0 0 0 0 0 1\n"), "bad.g2o:1: 'x' is not a vertex id");
  EXPECT_EQ(ErrorOf("VERTEX_SE3:QUAT\n"), "bad.g2o:1: VERTEX_SE3:QUAT without an id");
  EXPECT_EQ(ErrorOf(v0 + "EDGE_SE3:QUAT 0\n"), "bad.g2o:2: EDGE_SE3:QUAT without two ids");
  EXPECT_EQ(ErrorOf(v0 + v0), "bad.g2o:2: vertex 0 defined twice");
  EXPECT_EQ(ErrorOf(v0 + Edge(0, 0)), "bad.g2o:2: edge from vertex 0 to itself");
  EXPECT_EQ(ErrorOf(v0 + v1 + Edge(0, 1) + Edge(1, 9)),
            "bad.g2o:4: edge names vertex 9, which has no VERTEX_SE3:QUAT line");
  EXPECT_EQ(ErrorOf(v0 + "FIX 0\nFIX 4\n"), "bad.g2o:3: FIX names vertex 4, which is not in the file");
  EXPECT_EQ(ErrorOf(v0 + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n"),
            "bad.g2o:2: 2D record EDGE_SE2 in an SE(3) graph (2D and 3D records cannot be mixed)");
  EXPECT_EQ(ErrorOf("VERTEX_SE3:EULER 0 0 0 0 0 0 0\n"),
            "bad.g2o:1: unsupported g2o record type 'VERTEX_SE3:EULER'");
  EXPECT_EQ(ErrorOf("# nothing\n"), "bad.g2o: no vertices and no edges");
}

TEST(G2oSe3IoTest, InformationMustGiveSeSyncWeights) {
  const std::string v = "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n";
  // Blocks whose inverse has a negative trace, then a singular (zero) translation block.
  EXPECT_EQ(ErrorOf(v + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 -1 0 0 0 0 0 -1 0 0 0 0 -1 0 0 0 1 0 0 1 0 1\n"),
            "bad.g2o:3: information matrix: the translation block has no positive finite inverse "
            "trace (SE-Sync weight -1.000000)");
  EXPECT_TRUE(ErrorOf(v + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 1 0 0 1 0 1\n")
                  .starts_with("bad.g2o:3: information matrix: the translation block"));
  EXPECT_EQ(ErrorOf(v + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 -1 0 0 -1 0 -1\n"),
            "bad.g2o:3: information matrix: the rotation block has no positive finite inverse "
            "trace (SE-Sync weight -0.500000)");
  // Indefinite but with positive weights (as 5021 of cubicle's): read as it is.
  const Se3PoseGraph graph =
      ReadText(v + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 100 0 0 0 0 0 100 0 0 0 0 100 0 0 0 10 84022 132748 10 0 91520\n");
  EXPECT_EQ(graph.betweens.front().information(3, 4), 84022.0);
}

TEST(G2oSe3IoTest, EdgesOnlyFileHasNodesWithoutEstimates) {
  const Se3PoseGraph graph = ReadText(Edge(0, 1) + Edge(1, 2));
  ASSERT_EQ(graph.nodes.size(), 3u);
  EXPECT_FALSE(graph.nodes[1].has_estimate);
}

TEST(G2oSe3IoTest, FileFrontDoorTellsThreeFromTwoDimensions) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "flat2d_g2o_se3_io_test";
  std::filesystem::create_directories(dir);
  const std::string three_d = (dir / "cube.g2o").string();
  std::ofstream(three_d) << "# header\nFIX 3\n" << kG2oSe3;
  const std::string no_extension = (dir / "cube").string();
  std::ofstream(no_extension) << kG2oSe3;
  const std::string two_d = (dir / "square.g2o").string();
  std::ofstream(two_d) << "VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n";
  EXPECT_EQ(*DetectGraphFormat(three_d), GraphFormat::kG2oSe3);
  EXPECT_EQ(*DetectGraphFormat(no_extension), GraphFormat::kG2oSe3);
  EXPECT_EQ(*DetectGraphFormat(two_d), GraphFormat::kG2o);
  EXPECT_EQ(GraphFormatName(GraphFormat::kG2oSe3), "g2o_se3");
  const Result<PoseGraph> as_2d = ReadPoseGraphFile(three_d);
  ASSERT_FALSE(as_2d.ok());
  EXPECT_EQ(as_2d.error().message,
            three_d + ": an SE(3) pose graph (VERTEX_SE3:QUAT / EDGE_SE3:QUAT), not SE(2)");
  const Result<Se3PoseGraph> graph = ReadG2oSe3File(three_d);
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  EXPECT_EQ(graph->nodes.size(), 3u);
  EXPECT_EQ(ReadG2oSe3File((dir / "missing.g2o").string()).error().message,
            (dir / "missing.g2o").string() + ": cannot open");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace flat2d::localization::graph
