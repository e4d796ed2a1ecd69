// flat2d-graph: optimize a pose graph file (2D g2o or TORO, 3D g2o) and write the result as
// g2o of the same dimension. Steps: read (format by extension or content) -> initialize
// (file values, odometry chain or chordal) -> choose the objective (g2o chi2 or SE-Sync's f)
// -> sparse GN / LM in SE(2) or SE(3) -> print the initial and final cost in both
// conventions of REFERENCE_RESULTS.md -> write g2o.
// Exit status: 0 ok (also when the solver stopped without converging: see stop_reason),
// 1 usage or option error, 2 a file cannot be read, is invalid or cannot be written.
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>

#include "localization/graph/g2o_io.hpp"
#include "localization/graph/graph_costs.hpp"
#include "localization/graph/graph_file.hpp"
#include "localization/graph/graph_init.hpp"
#include "localization/graph/graph_optimizer.hpp"
#include "localization/graph/g2o_se3_io.hpp"
#include "localization/graph/se3_costs.hpp"
#include "localization/graph/se3_graph_optimizer.hpp"
#include "localization/graph/se3_init.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;
using namespace flat2d::localization::graph;

constexpr std::string_view kTool = "flat2d-graph";
constexpr const char* kUsage = R"(usage:
  flat2d-graph optimize IN OUT [--init file|odometry|chordal] [--solver gn|lm]
                               [--cost g2o|sesync] [--max-iterations N] [--json]
      IN                pose graph: 2D g2o (VERTEX_SE2/EDGE_SE2/FIX), 3D g2o
                        (VERTEX_SE3:QUAT/EDGE_SE3:QUAT/FIX) or 2D TORO (VERTEX2/EDGE2), told
                        apart by extension (.graph) and the first record
      OUT               the optimized graph, g2o format of IN's dimension
      --init            file: the file's vertex values, or the odometry chain when it has
                        none (default); odometry: compose edges i -> i+1 from vertex 0;
                        chordal: linear orientations, then linear positions (LAGO-style;
                        in 3D the 9 entries of each rotation, projected onto SO(3))
      --solver          lm: Levenberg-Marquardt (default); gn: Gauss-Newton
      --cost            the objective minimized: g2o chi2 with the file's information
                        (default, maximum likelihood) or SE-Sync's f (isotropic weights)
      --max-iterations  linear solves at most (default 100)
      --json            one JSON object on stdout instead of text
Both costs are printed either way: g2o chi2 = sum e^T L e; SE-Sync f = sum tau |dt|^2 +
kappa |dR|_F^2 (../shared/data/posegraph/REFERENCE_RESULTS.md, section 1; no factor 1/2).
In 3D, g2o's error is its own: [translation; quaternion vector part] of inv(z) inv(Xi) Xj.
)";

struct Options {
  std::string input;
  std::string output;
  Initialization init = Initialization::kFile;
  Solver solver = Solver::kLevenbergMarquardt;
  bool sesync_cost = false;
  int max_iterations = 100;
  bool json = false;
};

[[noreturn]] void Fail(int status, const std::string& message) {
  maps::cli::Fail(kTool, status, message);
}

Initialization ParseInit(std::string_view text) {
  if (text == "file") return Initialization::kFile;
  if (text == "odometry") return Initialization::kOdometry;
  if (text == "chordal") return Initialization::kChordal;
  Fail(1, "--init must be file, odometry or chordal, not '" + std::string(text) + "'");
}

Options Parse(int argc, char** argv) {
  if (argc < 2) Fail(1, std::string("no command\n") + kUsage);
  const std::string_view command = argv[1];
  if (command == "--help" || command == "-h") std::cout << kUsage, std::exit(0);
  if (command != "optimize") Fail(1, "unknown command '" + std::string(command) + "'\n" + kUsage);
  Options options;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) Fail(1, std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (arg == "--init") {
      options.init = ParseInit(value());
    } else if (arg == "--solver") {
      const std::string solver = value();
      if (solver != "gn" && solver != "lm") Fail(1, "--solver must be gn or lm, not '" + solver + "'");
      options.solver = solver == "gn" ? Solver::kGaussNewton : Solver::kLevenbergMarquardt;
    } else if (arg == "--cost") {
      const std::string cost = value();
      if (cost != "g2o" && cost != "sesync") Fail(1, "--cost must be g2o or sesync, not '" + cost + "'");
      options.sesync_cost = cost == "sesync";
    } else if (arg == "--max-iterations") {
      const std::string text = value();
      options.max_iterations =
          static_cast<int>(maps::cli::ParseInteger(kTool, arg, text.c_str(), 1, 1000000));
    } else if (arg == "--json") {
      options.json = true;
    } else if (arg == "--help" || arg == "-h") {
      std::cout << kUsage, std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      Fail(1, "unknown option " + std::string(arg) + "\n" + kUsage);
    } else if (options.input.empty()) {
      options.input = arg;
    } else if (options.output.empty()) {
      options.output = arg;
    } else {
      Fail(1, "more than two files given");
    }
  }
  if (options.output.empty()) Fail(1, "optimize needs IN and OUT\n" + std::string(kUsage));
  return options;
}

struct Costs {
  double g2o_chi2;
  double sesync_f;
};

// A JSON string literal: quotes, backslashes and control characters escaped.
std::string Quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out.push_back('\\');
      out.push_back(c);
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned>(c));
      out.append(escaped);
    } else {
      out.push_back(c);
    }
  }
  out.push_back('"');
  return out;
}

// What one optimization did, whatever the graph's dimension.
struct Summary {
  GraphFormat format = GraphFormat::kG2o;
  std::size_t nodes = 0;
  std::size_t edges = 0;
  Costs initial{};
  Costs final_costs{};
  OptimizationResult result;
};

int Dimension(GraphFormat format) { return format == GraphFormat::kG2oSe3 ? 3 : 2; }

std::string Json(const Options& o, const Summary& m) {
  const OptimizationResult& r = m.result;
  std::ostringstream s;
  s << std::setprecision(10) << "{\"input\": " << Quoted(o.input) << ", \"format\": \""
    << GraphFormatName(m.format) << "\", \"dimension\": " << Dimension(m.format)
    << ", \"output\": " << Quoted(o.output) << ", \"nodes\": " << m.nodes
    << ", \"edges\": " << m.edges << ", \"init\": \"" << InitializationName(o.init)
    << "\", \"solver\": \"" << (o.solver == Solver::kGaussNewton ? "gn" : "lm")
    << "\", \"cost\": \"" << (o.sesync_cost ? "sesync" : "g2o")
    << "\", \"initial\": {\"g2o_chi2\": " << m.initial.g2o_chi2
    << ", \"sesync_f\": " << m.initial.sesync_f << "}, \"final\": {\"g2o_chi2\": "
    << m.final_costs.g2o_chi2 << ", \"sesync_f\": " << m.final_costs.sesync_f
    << "}, \"iterations\": " << r.iterations << ", \"stop_reason\": \""
    << StopReasonName(r.stop_reason) << "\", \"converged\": " << (r.converged() ? "true" : "false")
    << ", \"seconds\": " << r.seconds << "}";
  return s.str();
}

void PrintText(const Summary& m) {
  const OptimizationResult& r = m.result;
  std::cout << std::setprecision(8) << "graph:       " << m.nodes << " nodes, " << m.edges
            << " edges (" << GraphFormatName(m.format) << ")\n"
            << "g2o chi2:    " << m.initial.g2o_chi2 << " -> " << m.final_costs.g2o_chi2 << "\n"
            << "SE-Sync f:   " << m.initial.sesync_f << " -> " << m.final_costs.sesync_f << "\n"
            << "iterations:  " << r.iterations << " (" << StopReasonName(r.stop_reason) << ")\n"
            << "time:        " << r.seconds << " s\n";
}

// Read, initialize, optimize the chosen objective, write: the same steps in SE(2) and SE(3),
// whose graph types have the same free functions.
template <typename Graph>
Summary OptimizeFile(const Options& options, GraphFormat format, Result<Graph> graph,
                     Status (*write)(const Graph&, const std::string&)) {
  if (!graph) Fail(2, graph.error().message);
  if (Status s = Initialize(*graph, options.init); !s) Fail(2, s.error().message);
  Summary summary{format, graph->nodes.size(), graph->betweens.size(),
                  {G2oChi2(*graph), SeSyncCost(*graph)}, {}, {}};
  Graph problem = options.sesync_cost ? ToSeSyncProblem(*graph) : *graph;
  summary.result =
      Optimize(problem, {.solver = options.solver, .max_iterations = options.max_iterations});
  for (std::size_t n = 0; n < graph->nodes.size(); ++n) {
    graph->nodes[n].estimate = problem.nodes[n].estimate;
  }
  summary.final_costs = {G2oChi2(*graph), SeSyncCost(*graph)};
  if (Status s = write(*graph, options.output); !s) Fail(2, s.error().message);
  return summary;
}

int Optimize(const Options& options) {
  const Result<GraphFormat> format = DetectGraphFormat(options.input);
  if (!format) Fail(2, format.error().message);
  const Summary summary =
      *format == GraphFormat::kG2oSe3
          ? OptimizeFile(options, *format, ReadG2oSe3File(options.input), &WriteG2oSe3File)
          : OptimizeFile(options, *format, ReadPoseGraphFile(options.input), &WriteG2oFile);
  if (options.json) {
    std::cout << Json(options, summary) << "\n";
  } else {
    PrintText(summary);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return Optimize(Parse(argc, argv)); }
