#include "localization/graph/g2o_io.hpp"

#include <array>
#include <fstream>
#include <limits>

#include "localization/graph/graph_text.hpp"

namespace flat2d::localization::graph {
namespace {

// The upper triangle I11 I12 I13 I22 I23 I33, row by row.
Eigen::Matrix3d FromUpperTriangle(const std::array<double, 6>& v) {
  Eigen::Matrix3d m;
  m << v[0], v[1], v[2],  //
      v[1], v[3], v[4],   //
      v[2], v[4], v[5];
  return m;
}

bool Is3dTag(std::string_view tag) {
  return tag.starts_with("VERTEX_SE3") || tag.starts_with("EDGE_SE3") ||
         tag.starts_with("VERTEX3") || tag.starts_with("EDGE3");
}

Status ParseG2oRecord(const std::vector<std::string_view>& fields, GraphTextBuilder& builder,
                   int line) {
  const std::string_view tag = fields.front();
  const std::string& source = builder.source();
  if (tag == "VERTEX_SE2") {
    int id = 0;
    std::array<double, 3> v{};
    if (fields.size() < 2) return LineError(source, line, "VERTEX_SE2 without an id");
    if (Status s = ParseId(fields[1], id, source, line); !s) return s;
    if (Status s = ParseNumbers(fields, 2, v, source, line); !s) return s;
    return builder.AddVertex(id, Se2(v[0], v[1], v[2]), line);
  }
  if (tag == "EDGE_SE2") {
    int from = 0;
    int to = 0;
    std::array<double, 9> v{};
    if (fields.size() < 3) return LineError(source, line, "EDGE_SE2 without two ids");
    if (Status s = ParseId(fields[1], from, source, line); !s) return s;
    if (Status s = ParseId(fields[2], to, source, line); !s) return s;
    if (Status s = ParseNumbers(fields, 3, v, source, line); !s) return s;
    return builder.AddEdge(from, to, Se2(v[0], v[1], v[2]),
                           FromUpperTriangle({v[3], v[4], v[5], v[6], v[7], v[8]}), line);
  }
  if (tag == "FIX") {
    if (fields.size() < 2) return LineError(source, line, "FIX without an id");
    for (std::size_t k = 1; k < fields.size(); ++k) {
      int id = 0;
      if (Status s = ParseId(fields[k], id, source, line); !s) return s;
      builder.AddFixed(id);
    }
    return Status::Ok();
  }
  if (Is3dTag(tag)) {
    return LineError(source, line,
                     "3D record " + std::string(tag) +
                         " in an SE(2) graph (2D and 3D records cannot be mixed)");
  }
  return LineError(source, line, "unsupported g2o record type '" + std::string(tag) + "'");
}

}  // namespace

Result<PoseGraph> ReadG2o(std::istream& in, const std::string& source) {
  GraphTextBuilder builder(source);
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::vector<std::string_view> fields = SplitFields(text);
    if (fields.empty() || fields.front().starts_with('#')) continue;
    if (Status s = ParseG2oRecord(fields, builder, line); !s) return s.error();
  }
  if (in.bad()) return MakeError(source + ": read error");
  return builder.Build();
}

Result<PoseGraph> ReadG2oFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return MakeError(path + ": cannot open");
  return ReadG2o(in, path);
}

Status WriteG2o(const PoseGraph& graph, std::ostream& out) {
  out.precision(std::numeric_limits<double>::max_digits10);
  for (const PoseNode& node : graph.nodes) {
    const Se2& p = node.estimate;
    out << "VERTEX_SE2 " << node.id << ' ' << p.x() << ' ' << p.y() << ' ' << p.theta() << '\n';
  }
  for (const PoseNode& node : graph.nodes) {
    if (node.fixed) out << "FIX " << node.id << '\n';
  }
  for (const BetweenFactor& f : graph.betweens) {
    const Se2& z = f.measurement;
    const Eigen::Matrix3d& l = f.information;
    out << "EDGE_SE2 " << graph.nodes[f.from].id << ' ' << graph.nodes[f.to].id << ' ' << z.x()
        << ' ' << z.y() << ' ' << z.theta() << ' ' << l(0, 0) << ' ' << l(0, 1) << ' ' << l(0, 2)
        << ' ' << l(1, 1) << ' ' << l(1, 2) << ' ' << l(2, 2) << '\n';
  }
  if (!out) return MakeError("g2o: write error");
  return Status::Ok();
}

Status WriteG2oFile(const PoseGraph& graph, const std::string& path) {
  std::ofstream out(path);
  if (!out) return MakeError(path + ": cannot open for writing");
  if (Status s = WriteG2o(graph, out); !s) return MakeError(path + ": write error");
  out.close();
  if (!out) return MakeError(path + ": write error");
  return Status::Ok();
}

}  // namespace flat2d::localization::graph
