#include "localization/graph/graph_text.hpp"

#include <charconv>
#include <cmath>
#include <set>
#include <utility>

namespace flat2d::localization::graph {

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t pos = 0;
  while (pos < line.size()) {
    const std::size_t start = line.find_first_not_of(" \t\r", pos);
    if (start == std::string_view::npos) break;
    const std::size_t end = std::min(line.find_first_of(" \t\r", start), line.size());
    fields.push_back(line.substr(start, end - start));
    pos = end;
  }
  return fields;
}

Error LineError(std::string_view source, int line, const std::string& what) {
  std::string message(source);
  message.append(":").append(std::to_string(line)).append(": ").append(what);
  return MakeError(std::move(message));
}

Status ParseNumbers(const std::vector<std::string_view>& fields, std::size_t first,
                    std::span<double> out, std::string_view source, int line) {
  if (fields.size() != first + out.size()) {
    return LineError(source, line,
                     std::string(fields.front()) + " needs " + std::to_string(out.size()) +
                         " numbers after its ids, found " +
                         std::to_string(static_cast<long>(fields.size()) -
                                        static_cast<long>(first)));
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    const std::string_view field = fields[first + k];
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), out[k]);
    if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(out[k])) {
      std::string what = "field ";
      what.append(std::to_string(first + k + 1)).append(" '").append(field);
      what.append("' is not a finite number");
      return LineError(source, line, what);
    }
  }
  return Status::Ok();
}

Status ParseId(std::string_view field, int& id, std::string_view source, int line) {
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), id);
  if (ec != std::errc() || end != field.data() + field.size() || id < 0) {
    std::string what = "'";
    what.append(field).append("' is not a vertex id");
    return LineError(source, line, what);
  }
  return Status::Ok();
}

Status GraphTextBuilder::AddVertex(int id, const Se2& pose, int line) {
  if (!vertices_.emplace(id, pose).second) {
    return LineError(source_, line, "vertex " + std::to_string(id) + " defined twice");
  }
  return Status::Ok();
}

Status GraphTextBuilder::AddEdge(int from_id, int to_id, const Se2& measurement,
                                 const Eigen::Matrix3d& information, int line) {
  if (from_id == to_id) {
    return LineError(source_, line, "edge from vertex " + std::to_string(from_id) + " to itself");
  }
  edges_.push_back({from_id, to_id, measurement, information});
  return Status::Ok();
}

Result<PoseGraph> GraphTextBuilder::Build() const {
  std::set<int> ids;
  for (const auto& [id, pose] : vertices_) ids.insert(id);
  for (const Edge& edge : edges_) {
    ids.insert(edge.from_id);
    ids.insert(edge.to_id);
  }
  if (ids.empty()) return MakeError(source_ + ": no vertices and no edges");
  PoseGraph graph;
  std::map<int, std::size_t> index_of;
  for (const int id : ids) {
    const auto vertex = vertices_.find(id);
    const bool known = vertex != vertices_.end();
    index_of[id] = graph.nodes.size();
    graph.nodes.push_back({id, known ? vertex->second : Se2(), false, known});
  }
  for (const int id : fixed_ids_) {
    const auto found = index_of.find(id);
    if (found == index_of.end()) {
      return MakeError(source_ + ": FIX names vertex " + std::to_string(id) + ", which is not in the file");
    }
    graph.nodes[found->second].fixed = true;
  }
  graph.betweens.reserve(edges_.size());
  for (const Edge& edge : edges_) {
    graph.betweens.push_back({index_of[edge.from_id], index_of[edge.to_id], edge.measurement,
                              edge.information, AngleResidual::kWrapped});
  }
  return graph;
}

}  // namespace flat2d::localization::graph
