#include "localization/graph/g2o_se3_io.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include "localization/graph/graph_text.hpp"
#include "localization/graph/se3_costs.hpp"

namespace flat2d::localization::graph {
namespace {

// Files print quaternions with 6-7 significant digits; anything further from unit norm
// is not a rotation written with rounding but a broken record.
constexpr double kQuaternionNormTolerance = 1e-3;

constexpr std::string_view kVertexTag = "VERTEX_SE3:QUAT";
constexpr std::string_view kEdgeTag = "EDGE_SE3:QUAT";

// x y z qx qy qz qw -> the pose; an error unless the quaternion is unit within tolerance.
Result<Eigen::Isometry3d> PoseOf(std::span<const double> v, std::string_view source, int line) {
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // (w, x, y, z)
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    return LineError(source, line, "quaternion norm " + std::to_string(norm) +
                                       " is not 1: not a rotation");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return pose;
}

// The upper triangle I11 .. I16 I22 .. I66 row by row -> the symmetric matrix; an error
// unless both diagonal blocks give SE-Sync a positive weight (a positive finite trace of
// their inverse). Definiteness is not required: g2o and SE-Sync read the published cubicle
// graph, 5021 of whose 16869 matrices are indefinite, as it is.
Result<Matrix6d> InformationOf(std::span<const double> v, std::string_view source, int line) {
  Matrix6d information;
  std::size_t k = 0;
  for (int r = 0; r < 6; ++r) {
    for (int c = r; c < 6; ++c) information(r, c) = information(c, r) = v[k++];
  }
  const SeSyncWeights w = SeSyncWeightsOf(information);
  for (const auto& [weight, block] : {std::pair{w.tau, "translation"}, std::pair{w.kappa, "rotation"}}) {
    if (!(weight > 0.0) || !std::isfinite(weight)) {
      return LineError(source, line,
                       std::string("information matrix: the ") + block +
                           " block has no positive finite inverse trace (SE-Sync weight " +
                           std::to_string(weight) + ")");
    }
  }
  return information;
}

// A file's records before ids become indices (edges may come before their vertices).
class Se3Records {
 public:
  explicit Se3Records(std::string source) : source_(std::move(source)) {}

  Status Parse(const std::vector<std::string_view>& fields, int line);
  Result<Se3PoseGraph> Build() const;

 private:
  struct Edge {
    int from_id;
    int to_id;
    Eigen::Isometry3d measurement;
    Matrix6d information;
    int line;
  };
  Status ParseVertex(const std::vector<std::string_view>& fields, int line);
  Status ParseEdge(const std::vector<std::string_view>& fields, int line);
  Status ParseFix(const std::vector<std::string_view>& fields, int line);
  Status CheckEdgeIds() const;

  std::string source_;
  std::map<int, Eigen::Isometry3d> vertices_;
  std::vector<Edge> edges_;
  std::vector<std::pair<int, int>> fixed_;  // (id, line)
};

Status Se3Records::Parse(const std::vector<std::string_view>& fields, int line) {
  const std::string_view tag = fields.front();
  if (tag == kVertexTag) return ParseVertex(fields, line);
  if (tag == kEdgeTag) return ParseEdge(fields, line);
  if (tag == "FIX") return ParseFix(fields, line);
  if (tag == "VERTEX_SE2" || tag == "EDGE_SE2") {
    return LineError(source_, line, "2D record " + std::string(tag) +
                                        " in an SE(3) graph (2D and 3D records cannot be mixed)");
  }
  return LineError(source_, line, "unsupported g2o record type '" + std::string(tag) + "'");
}

Status Se3Records::ParseVertex(const std::vector<std::string_view>& fields, int line) {
  int id = 0;
  std::array<double, 7> v{};
  if (fields.size() < 2) return LineError(source_, line, "VERTEX_SE3:QUAT without an id");
  if (Status s = ParseId(fields[1], id, source_, line); !s) return s;
  if (Status s = ParseNumbers(fields, 2, v, source_, line); !s) return s;
  Result<Eigen::Isometry3d> pose = PoseOf(v, source_, line);
  if (!pose) return pose.error();
  if (!vertices_.emplace(id, *pose).second) {
    return LineError(source_, line, "vertex " + std::to_string(id) + " defined twice");
  }
  return Status::Ok();
}

Status Se3Records::ParseEdge(const std::vector<std::string_view>& fields, int line) {
  int from = 0;
  int to = 0;
  std::array<double, 28> v{};
  if (fields.size() < 3) return LineError(source_, line, "EDGE_SE3:QUAT without two ids");
  if (Status s = ParseId(fields[1], from, source_, line); !s) return s;
  if (Status s = ParseId(fields[2], to, source_, line); !s) return s;
  if (Status s = ParseNumbers(fields, 3, v, source_, line); !s) return s;
  if (from == to) {
    return LineError(source_, line, "edge from vertex " + std::to_string(from) + " to itself");
  }
  Result<Eigen::Isometry3d> measurement = PoseOf(std::span(v).first(7), source_, line);
  if (!measurement) return measurement.error();
  Result<Matrix6d> information = InformationOf(std::span(v).subspan(7), source_, line);
  if (!information) return information.error();
  edges_.push_back({from, to, *measurement, *information, line});
  return Status::Ok();
}

Status Se3Records::ParseFix(const std::vector<std::string_view>& fields, int line) {
  if (fields.size() < 2) return LineError(source_, line, "FIX without an id");
  for (std::size_t k = 1; k < fields.size(); ++k) {
    int id = 0;
    if (Status s = ParseId(fields[k], id, source_, line); !s) return s;
    fixed_.emplace_back(id, line);
  }
  return Status::Ok();
}

Status Se3Records::CheckEdgeIds() const {
  if (vertices_.empty()) return Status::Ok();  // edges only: nodes without estimates
  for (const Edge& edge : edges_) {
    for (const int id : {edge.from_id, edge.to_id}) {
      if (!vertices_.contains(id)) {
        return LineError(source_, edge.line,
                         "edge names vertex " + std::to_string(id) + ", which has no " +
                             std::string(kVertexTag) + " line");
      }
    }
  }
  return Status::Ok();
}

Result<Se3PoseGraph> Se3Records::Build() const {
  if (Status s = CheckEdgeIds(); !s) return s.error();
  std::set<int> ids;
  for (const auto& [id, pose] : vertices_) ids.insert(id);
  for (const Edge& edge : edges_) ids.insert({edge.from_id, edge.to_id});
  if (ids.empty()) return MakeError(source_ + ": no vertices and no edges");
  Se3PoseGraph graph;
  std::map<int, std::size_t> index_of;
  for (const int id : ids) {
    const auto vertex = vertices_.find(id);
    const bool known = vertex != vertices_.end();
    index_of[id] = graph.nodes.size();
    graph.nodes.push_back(
        {id, known ? vertex->second : Eigen::Isometry3d::Identity(), false, known});
  }
  for (const auto& [id, line] : fixed_) {
    const auto found = index_of.find(id);
    if (found == index_of.end()) {
      return LineError(source_, line,
                       "FIX names vertex " + std::to_string(id) + ", which is not in the file");
    }
    graph.nodes[found->second].fixed = true;
  }
  graph.betweens.reserve(edges_.size());
  for (const Edge& edge : edges_) {
    graph.betweens.push_back(
        {index_of[edge.from_id], index_of[edge.to_id], edge.measurement, edge.information});
  }
  return graph;
}

void WritePose(std::ostream& out, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d& t = pose.translation();
  const Eigen::Quaterniond q(pose.linear());
  out << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
      << ' ' << q.w();
}

}  // namespace

Result<Se3PoseGraph> ReadG2oSe3(std::istream& in, const std::string& source) {
  Se3Records records(source);
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::vector<std::string_view> fields = SplitFields(text);
    if (fields.empty() || fields.front().starts_with('#')) continue;
    if (Status s = records.Parse(fields, line); !s) return s.error();
  }
  if (in.bad()) return MakeError(source + ": read error");
  return records.Build();
}

Result<Se3PoseGraph> ReadG2oSe3File(const std::string& path) {
  std::ifstream in(path);
  if (!in) return MakeError(path + ": cannot open");
  return ReadG2oSe3(in, path);
}

Status WriteG2oSe3(const Se3PoseGraph& graph, std::ostream& out) {
  out.precision(std::numeric_limits<double>::max_digits10);
  for (const Se3Node& node : graph.nodes) {
    out << kVertexTag << ' ' << node.id << ' ';
    WritePose(out, node.estimate);
    out << '\n';
  }
  for (const Se3Node& node : graph.nodes) {
    if (node.fixed) out << "FIX " << node.id << '\n';
  }
  for (const Se3BetweenFactor& f : graph.betweens) {
    out << kEdgeTag << ' ' << graph.nodes[f.from].id << ' ' << graph.nodes[f.to].id << ' ';
    WritePose(out, f.measurement);
    for (int r = 0; r < 6; ++r) {
      for (int c = r; c < 6; ++c) out << ' ' << f.information(r, c);
    }
    out << '\n';
  }
  if (!out) return MakeError("g2o: write error");
  return Status::Ok();
}

Status WriteG2oSe3File(const Se3PoseGraph& graph, const std::string& path) {
  std::ofstream out(path);
  if (!out) return MakeError(path + ": cannot open for writing");
  if (Status s = WriteG2oSe3(graph, out); !s) return MakeError(path + ": write error");
  out.close();
  if (!out) return MakeError(path + ": write error");
  return Status::Ok();
}

}  // namespace flat2d::localization::graph
