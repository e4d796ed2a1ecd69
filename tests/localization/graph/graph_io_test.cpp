// g2o and TORO files: round trips keep ids, poses, information and FIX; malformed lines fail
// with the line number; 3D records are refused by the 2D reader (g2o_se3_io_test.cpp reads
// them); TORO's information is rotated into g2o's frame (checked against the two formats of
// CSAIL and M3500 shipped in ../shared/data).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "localization/graph/g2o_io.hpp"
#include "localization/graph/graph_file.hpp"
#include "localization/graph/toro_io.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::localization::graph {
namespace {

constexpr const char* kG2o = R"(# a comment
VERTEX_SE2 10 0 0 0
VERTEX_SE2 11 1.0 0.5 0.3
VERTEX_SE2 13 2.0 1.0 -3.1
EDGE_SE2 10 11 1.0 0.5 0.3 100 1 2 200 3 1000
EDGE_SE2 11 13 1.0 0.2 2.9 50 0 0 60 0 500

EDGE_SE2 10 13 2.0 1.0 -3.1 10 0 0 10 0 10
FIX 10
)";

PoseGraph ReadG2oText(const std::string& text) {
  std::istringstream in(text);
  Result<PoseGraph> graph = ReadG2o(in, "test.g2o");
  EXPECT_TRUE(graph.ok()) << graph.error().message;
  return std::move(graph).value();
}

std::string ErrorOf(const std::string& text, bool toro = false) {
  std::istringstream in(text);
  const Result<PoseGraph> graph = toro ? ReadToro(in, "bad") : ReadG2o(in, "bad");
  EXPECT_FALSE(graph.ok()) << text;
  return graph.ok() ? std::string() : graph.error().message;
}

void ExpectSameGraph(const PoseGraph& a, const PoseGraph& b, double tolerance) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.betweens.size(), b.betweens.size());
  for (std::size_t n = 0; n < a.nodes.size(); ++n) {
    EXPECT_EQ(a.nodes[n].id, b.nodes[n].id);
    EXPECT_TRUE(a.nodes[n].estimate.Vector().isApprox(b.nodes[n].estimate.Vector(), tolerance));
  }
  for (std::size_t e = 0; e < a.betweens.size(); ++e) {
    EXPECT_EQ(a.betweens[e].from, b.betweens[e].from);
    EXPECT_EQ(a.betweens[e].to, b.betweens[e].to);
    EXPECT_TRUE(a.betweens[e].measurement.Vector().isApprox(b.betweens[e].measurement.Vector(),
                                                            tolerance));
    EXPECT_TRUE(a.betweens[e].information.isApprox(b.betweens[e].information, tolerance))
        << a.betweens[e].information << "\nvs\n" << b.betweens[e].information;
  }
}

TEST(G2oIoTest, ReadsVerticesEdgesAndFix) {
  const PoseGraph graph = ReadG2oText(kG2o);
  ASSERT_EQ(graph.nodes.size(), 3u);
  EXPECT_EQ(graph.nodes[2].id, 13);
  EXPECT_TRUE(graph.nodes[0].fixed);
  EXPECT_FALSE(graph.nodes[1].fixed);
  EXPECT_NEAR(graph.nodes[2].estimate.theta(), -3.1, 1e-12);
  ASSERT_EQ(graph.betweens.size(), 3u);
  EXPECT_EQ(graph.betweens[1].from, 1u);
  EXPECT_EQ(graph.betweens[1].to, 2u);
  Eigen::Matrix3d expected;
  expected << 100, 1, 2, 1, 200, 3, 2, 3, 1000;  // upper triangle mirrored
  EXPECT_EQ(graph.betweens[0].information, expected);
}

TEST(G2oIoTest, RoundTripKeepsEverything) {
  const PoseGraph graph = ReadG2oText(kG2o);
  std::ostringstream out;
  ASSERT_TRUE(WriteG2o(graph, out).ok());
  const PoseGraph again = ReadG2oText(out.str());
  ExpectSameGraph(graph, again, 1e-15);
  EXPECT_TRUE(again.nodes[0].fixed);
}

TEST(G2oIoTest, EdgesOnlyFileHasNodesWithoutEstimates) {
  const PoseGraph graph = ReadG2oText("EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\nEDGE_SE2 1 2 1 0 0 1 0 0 1 0 1\n");
  ASSERT_EQ(graph.nodes.size(), 3u);
  EXPECT_FALSE(graph.nodes[1].has_estimate);
}

TEST(G2oIoTest, MalformedLinesNameTheLine) {
  EXPECT_EQ(ErrorOf("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0\n"),
            "bad:2: VERTEX_SE2 needs 3 numbers after its ids, found 2");
  EXPECT_EQ(ErrorOf("\n\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 x\n"),
            "bad:3: field 12 'x' is not a finite number");
  EXPECT_EQ(ErrorOf("VERTEX_SE2 -1 0 0 0\n"), "bad:1: '-1' is not a vertex id");
  EXPECT_EQ(ErrorOf("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 0 1 0 0\n"), "bad:2: vertex 0 defined twice");
  EXPECT_EQ(ErrorOf("EDGE_SE2 3 3 1 0 0 1 0 0 1 0 1\n"), "bad:1: edge from vertex 3 to itself");
  EXPECT_EQ(ErrorOf("VERTEX_SE2 0 0 0 nan\n"), "bad:1: field 5 'nan' is not a finite number");
  EXPECT_EQ(ErrorOf("VERTEX_SE2 0 0 0 0\nFIX 7\n"), "bad: FIX names vertex 7, which is not in the file");
  EXPECT_EQ(ErrorOf("VERTEX_XY 0 1 2\n"), "bad:1: unsupported g2o record type 'VERTEX_XY'");
  EXPECT_EQ(ErrorOf(""), "bad: no vertices and no edges");
}

TEST(G2oIoTest, ThreeDimensionalRecordsAreRefusedClearly) {
  EXPECT_EQ(ErrorOf("VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"),
            "bad:1: 3D record VERTEX_SE3:QUAT in an SE(2) graph (2D and 3D records cannot be mixed)");
}

TEST(ToroIoTest, RoundTripRotatesInformationBackAndForth) {
  const PoseGraph graph = ReadG2oText(kG2o);
  std::ostringstream out;
  ASSERT_TRUE(WriteToro(graph, out).ok());
  std::istringstream in(out.str());
  const Result<PoseGraph> again = ReadToro(in, "round.graph");
  ASSERT_TRUE(again.ok()) << again.error().message;
  ExpectSameGraph(graph, *again, 1e-12);
}

TEST(ToroIoTest, InformationOrderAndFrame) {
  // inf_xx inf_xy inf_yy inf_tt inf_xt inf_yt; with z_theta = 0 no rotation applies.
  std::istringstream in("EDGE2 0 1 1 0 0 1 2 3 4 5 6\n");
  const Result<PoseGraph> graph = ReadToro(in, "t");
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  Eigen::Matrix3d expected;
  expected << 1, 2, 5, 2, 3, 6, 5, 6, 4;
  EXPECT_EQ(graph->betweens[0].information, expected);
  EXPECT_EQ(ErrorOf("EDGE2 0 1 1 0 0 1 2 3 4 5\n", true),
            "bad:1: EDGE2 needs 9 numbers after its ids, found 8");
  EXPECT_EQ(ErrorOf("EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\n", true),
            "bad:1: unsupported TORO record type 'EDGE_SE2'");
}

TEST(ToroIoTest, SharedDatasetsAgreeWithTheirG2oVersions) {
  FLAT2D_REQUIRE_DATA(csail_g2o, "posegraph/g2o/CSAIL.g2o");
  FLAT2D_REQUIRE_DATA(csail_toro, "posegraph/toro/CSAIL_P_toro.graph");
  FLAT2D_REQUIRE_DATA(m3500_g2o, "posegraph/g2o/manhattan.g2o");
  FLAT2D_REQUIRE_DATA(m3500_toro, "posegraph/toro/M3500_P_toro.graph");
  for (const auto& [g2o_path, toro_path] :
       {std::pair{csail_g2o, csail_toro}, std::pair{m3500_g2o, m3500_toro}}) {
    const Result<PoseGraph> a = ReadPoseGraphFile(g2o_path.string());
    const Result<PoseGraph> b = ReadPoseGraphFile(toro_path.string());
    ASSERT_TRUE(a.ok()) << a.error().message;
    ASSERT_TRUE(b.ok()) << b.error().message;
    ASSERT_EQ(a->betweens.size(), b->betweens.size());
    double worst = 0.0;  // relative; both files print 6 decimals
    for (std::size_t e = 0; e < a->betweens.size(); ++e) {
      const Eigen::Matrix3d& la = a->betweens[e].information;
      const Eigen::Matrix3d& lb = b->betweens[e].information;
      worst = std::max(worst, (la - lb).cwiseAbs().maxCoeff() / la.cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-6) << toro_path;
  }
}

TEST(GraphFileTest, DetectsFormatByExtensionAndContent) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "flat2d_graph_io_test";
  std::filesystem::create_directories(dir);
  const std::string no_extension = (dir / "graph_g2o").string();
  std::ofstream(no_extension) << kG2o;
  const std::string toro_content = (dir / "graph_toro").string();
  std::ofstream(toro_content) << "VERTEX2 0 0 0 0\nVERTEX2 1 1 0 0\nEDGE2 0 1 1 0 0 1 0 1 1 0 0\n";
  const std::string unknown = (dir / "graph_unknown").string();
  std::ofstream(unknown) << "# header\nPOSE 0 1 2\n";
  EXPECT_EQ(*DetectGraphFormat(no_extension), GraphFormat::kG2o);
  EXPECT_EQ(*DetectGraphFormat(toro_content), GraphFormat::kToro);
  EXPECT_EQ(*DetectGraphFormat("x.graph"), GraphFormat::kToro);
  const Result<GraphFormat> bad = DetectGraphFormat(unknown);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message,
            unknown + ":2: unknown record 'POSE': neither a g2o nor a TORO pose graph");
  const Result<PoseGraph> toro = ReadPoseGraphFile(toro_content);
  ASSERT_TRUE(toro.ok()) << toro.error().message;
  EXPECT_EQ(toro->nodes.size(), 2u);
  EXPECT_FALSE(ReadPoseGraphFile((dir / "missing.g2o").string()).ok());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace flat2d::localization::graph
