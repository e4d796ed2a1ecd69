// What the g2o and TORO text readers share: splitting a line into fields, parsing numbers
// with the line number in every error, and assembling vertices, edges and FIX marks that
// refer to file ids into a PoseGraph whose nodes are sorted by id (so consecutive ids,
// the odometry chain, are consecutive indices).
#pragma once

#include <Eigen/Core>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/graph/pose_graph.hpp"

namespace flat2d::localization::graph {

// Whitespace-separated fields of one line (views into it).
std::vector<std::string_view> SplitFields(std::string_view line);

// "<source>:<line>: <what>".
Error LineError(std::string_view source, int line, const std::string& what);

// Parses fields[first, first + out.size()) as numbers; an error names the field.
Status ParseNumbers(const std::vector<std::string_view>& fields, std::size_t first,
                    std::span<double> out, std::string_view source, int line);
Status ParseId(std::string_view field, int& id, std::string_view source, int line);

// Collects a file's records; Build() maps ids to node indices.
class GraphTextBuilder {
 public:
  explicit GraphTextBuilder(std::string source) : source_(std::move(source)) {}
  const std::string& source() const { return source_; }

  Status AddVertex(int id, const Se2& pose, int line);
  // Errors: an edge from a node to itself, non-finite values.
  Status AddEdge(int from_id, int to_id, const Se2& measurement,
                 const Eigen::Matrix3d& information, int line);
  void AddFixed(int id) { fixed_ids_.push_back(id); }

  // Errors: no vertices and no edges, a FIX of an unknown id.
  Result<PoseGraph> Build() const;

 private:
  struct Edge {
    int from_id;
    int to_id;
    Se2 measurement;
    Eigen::Matrix3d information;
  };
  std::string source_;
  std::map<int, Se2> vertices_;
  std::vector<Edge> edges_;
  std::vector<int> fixed_ids_;
};

}  // namespace flat2d::localization::graph
