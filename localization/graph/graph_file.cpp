#include "localization/graph/graph_file.hpp"

#include <fstream>

#include "localization/graph/g2o_io.hpp"
#include "localization/graph/graph_text.hpp"
#include "localization/graph/toro_io.hpp"

namespace flat2d::localization::graph {
namespace {

bool EndsWith(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

}  // namespace

std::string_view GraphFormatName(GraphFormat format) {
  switch (format) {
    case GraphFormat::kG2o: return "g2o";
    case GraphFormat::kG2oSe3: return "g2o_se3";
    case GraphFormat::kToro: return "toro";
  }
  return "unknown";
}

Result<GraphFormat> DetectGraphFormat(const std::string& path) {
  if (EndsWith(path, ".graph") || EndsWith(path, ".toro")) return GraphFormat::kToro;
  std::ifstream in(path);
  if (!in) return MakeError(path + ": cannot open");
  // A .g2o file is g2o whatever its records: its reader names a bad one with its line.
  const bool g2o_extension = EndsWith(path, ".g2o");
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::vector<std::string_view> fields = SplitFields(text);
    if (fields.empty() || fields.front().starts_with('#')) continue;
    const std::string_view tag = fields.front();
    if (tag == "VERTEX_SE3:QUAT" || tag == "EDGE_SE3:QUAT") return GraphFormat::kG2oSe3;
    if (tag == "FIX") continue;  // says nothing of the dimension
    if (g2o_extension || tag.starts_with("VERTEX_") || tag.starts_with("EDGE_")) {
      return GraphFormat::kG2o;
    }
    if (tag == "VERTEX2" || tag == "EDGE2" || tag == "VERTEX3" || tag == "EDGE3") {
      return GraphFormat::kToro;
    }
    return LineError(path, line, "unknown record '" + std::string(tag) +
                                     "': neither a g2o nor a TORO pose graph");
  }
  if (g2o_extension) return GraphFormat::kG2o;
  return MakeError(path + ": empty file, no pose graph");
}

Result<PoseGraph> ReadPoseGraphFile(const std::string& path) {
  const Result<GraphFormat> format = DetectGraphFormat(path);
  if (!format) return format.error();
  switch (*format) {
    case GraphFormat::kG2o: return ReadG2oFile(path);
    case GraphFormat::kToro: return ReadToroFile(path);
    case GraphFormat::kG2oSe3: break;
  }
  return MakeError(path + ": an SE(3) pose graph (VERTEX_SE3:QUAT / EDGE_SE3:QUAT), not SE(2)");
}

}  // namespace flat2d::localization::graph
