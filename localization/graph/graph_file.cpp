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
  return format == GraphFormat::kG2o ? "g2o" : "toro";
}

Result<GraphFormat> DetectGraphFormat(const std::string& path) {
  if (EndsWith(path, ".g2o")) return GraphFormat::kG2o;
  if (EndsWith(path, ".graph") || EndsWith(path, ".toro")) return GraphFormat::kToro;
  std::ifstream in(path);
  if (!in) return MakeError(path + ": cannot open");
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    const std::vector<std::string_view> fields = SplitFields(text);
    if (fields.empty() || fields.front().starts_with('#')) continue;
    const std::string_view tag = fields.front();
    if (tag.starts_with("VERTEX_") || tag.starts_with("EDGE_") || tag == "FIX") {
      return GraphFormat::kG2o;
    }
    if (tag == "VERTEX2" || tag == "EDGE2" || tag == "VERTEX3" || tag == "EDGE3") {
      return GraphFormat::kToro;
    }
    return LineError(path, line, "unknown record '" + std::string(tag) +
                                     "': neither a g2o nor a TORO pose graph");
  }
  return MakeError(path + ": empty file, no pose graph");
}

Result<PoseGraph> ReadPoseGraphFile(const std::string& path) {
  const Result<GraphFormat> format = DetectGraphFormat(path);
  if (!format) return format.error();
  return *format == GraphFormat::kG2o ? ReadG2oFile(path) : ReadToroFile(path);
}

}  // namespace flat2d::localization::graph
