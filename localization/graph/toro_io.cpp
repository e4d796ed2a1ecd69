#include "localization/graph/toro_io.hpp"

#include <array>
#include <fstream>
#include <limits>

#include "localization/graph/graph_text.hpp"

namespace flat2d::localization::graph {
namespace {

// B = diag(Rz, 1): TORO's error is B times F2's (see the header).
Eigen::Matrix3d FrameRotation(const Se2& measurement) {
  Eigen::Matrix3d b = Eigen::Matrix3d::Identity();
  b.topLeftCorner<2, 2>() = measurement.Rotation();
  return b;
}

// TORO's order: inf_xx inf_xy inf_yy inf_tt inf_xt inf_yt.
Eigen::Matrix3d FromToroOrder(const std::array<double, 6>& v) {
  Eigen::Matrix3d m;
  m << v[0], v[1], v[4],  //
      v[1], v[2], v[5],   //
      v[4], v[5], v[3];
  return m;
}

Status ParseToroRecord(const std::vector<std::string_view>& fields, GraphTextBuilder& builder,
                   int line) {
  const std::string_view tag = fields.front();
  const std::string& source = builder.source();
  if (tag == "VERTEX2" || tag == "VERTEX") {
    int id = 0;
    std::array<double, 3> v{};
    if (fields.size() < 2) return LineError(source, line, "VERTEX2 without an id");
    if (Status s = ParseId(fields[1], id, source, line); !s) return s;
    if (Status s = ParseNumbers(fields, 2, v, source, line); !s) return s;
    return builder.AddVertex(id, Se2(v[0], v[1], v[2]), line);
  }
  if (tag == "EDGE2" || tag == "EDGE") {
    int from = 0;
    int to = 0;
    std::array<double, 9> v{};
    if (fields.size() < 3) return LineError(source, line, "EDGE2 without two ids");
    if (Status s = ParseId(fields[1], from, source, line); !s) return s;
    if (Status s = ParseId(fields[2], to, source, line); !s) return s;
    if (Status s = ParseNumbers(fields, 3, v, source, line); !s) return s;
    const Se2 z(v[0], v[1], v[2]);
    const Eigen::Matrix3d b = FrameRotation(z);
    const Eigen::Matrix3d toro = FromToroOrder({v[3], v[4], v[5], v[6], v[7], v[8]});
    return builder.AddEdge(from, to, z, b.transpose() * toro * b, line);
  }
  if (tag == "VERTEX3" || tag == "EDGE3") {
    return LineError(source, line,
                     "3D record " + std::string(tag) + " is not supported (SE(2) graphs only)");
  }
  return LineError(source, line, "unsupported TORO record type '" + std::string(tag) + "'");
}

}  // namespace

Result<PoseGraph> ReadToro(std::istream& in, const std::string& source) {
  GraphTextBuilder builder(source);
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::vector<std::string_view> fields = SplitFields(text);
    if (fields.empty() || fields.front().starts_with('#')) continue;
    if (Status s = ParseToroRecord(fields, builder, line); !s) return s.error();
  }
  if (in.bad()) return MakeError(source + ": read error");
  return builder.Build();
}

Result<PoseGraph> ReadToroFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return MakeError(path + ": cannot open");
  return ReadToro(in, path);
}

Status WriteToro(const PoseGraph& graph, std::ostream& out) {
  out.precision(std::numeric_limits<double>::max_digits10);
  for (const PoseNode& node : graph.nodes) {
    const Se2& p = node.estimate;
    out << "VERTEX2 " << node.id << ' ' << p.x() << ' ' << p.y() << ' ' << p.theta() << '\n';
  }
  for (const BetweenFactor& f : graph.betweens) {
    const Se2& z = f.measurement;
    const Eigen::Matrix3d b = FrameRotation(z);
    const Eigen::Matrix3d l = b * f.information * b.transpose();
    out << "EDGE2 " << graph.nodes[f.from].id << ' ' << graph.nodes[f.to].id << ' ' << z.x()
        << ' ' << z.y() << ' ' << z.theta() << ' ' << l(0, 0) << ' ' << l(0, 1) << ' ' << l(1, 1)
        << ' ' << l(2, 2) << ' ' << l(0, 2) << ' ' << l(1, 2) << '\n';
  }
  if (!out) return MakeError("toro: write error");
  return Status::Ok();
}

Status WriteToroFile(const PoseGraph& graph, const std::string& path) {
  std::ofstream out(path);
  if (!out) return MakeError(path + ": cannot open for writing");
  if (Status s = WriteToro(graph, out); !s) return MakeError(path + ": write error");
  out.close();
  if (!out) return MakeError(path + ": write error");
  return Status::Ok();
}

}  // namespace flat2d::localization::graph
