// flat2d-eval: estimates against references.
//   grid   structure precision and recall of a class grid against a truth grid (issue 6)
// Exit status: 0 ok, 1 usage or option error, 2 a file cannot be read or is invalid.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <string_view>

#include "maps/grid/class_grid_file.hpp"
#include "maps/grid/structure_comparison.hpp"
#include "maps/tools/cli_args.hpp"

namespace {

using namespace flat2d;

constexpr std::string_view kTool = "flat2d-eval";

constexpr const char* kUsage = R"(usage:
  flat2d-eval grid --truth A.yaml --grid B.yaml [--tolerance CELLS] [--observed-radius CELLS] [--json]

grid: slammable cells of grid B against the occupied (slammable) cells of truth A, both
map_server YAML + PGM files in one world frame (flat2d-sim's truth_map.yaml, flat2d-grid's
--out). precision: share of B's slammable cells within --tolerance truth cells (Chebyshev)
of true structure. recall: share of the truth's structure faces that B observed near (any
class within --observed-radius cells of the point that many + 1 cells in front of the
face) and found within --tolerance.
  --tolerance CELLS        default 1
  --observed-radius CELLS  default 2 (10 cm at 5 cm)
  --json                   one JSON object: precision, recall and the counts behind them
)";

[[noreturn]] void Fail(int status, const std::string& message) { maps::cli::Fail(kTool, status, message); }

int EvalGrid(int argc, char** argv) {
  std::string truth_path, grid_path;
  maps::StructureComparisonOptions options;
  bool json = false;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) Fail(1, std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--truth") truth_path = value();
    else if (arg == "--grid") grid_path = value();
    else if (arg == "--tolerance") {
      options.tolerance_cells = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 1000));
    } else if (arg == "--observed-radius") {
      options.observed_radius_cells = static_cast<int>(maps::cli::ParseInteger(kTool, arg, value(), 0, 100000));
    } else if (arg == "--json") json = true;
    else Fail(1, "unknown argument " + std::string(arg) + "\n" + kUsage);
  }
  if (truth_path.empty() || grid_path.empty()) Fail(1, std::string("grid needs --truth and --grid\n") + kUsage);
  auto truth = maps::ReadClassGrid(truth_path);
  if (!truth.ok()) Fail(2, truth.error().message);
  auto grid = maps::ReadClassGrid(grid_path);
  if (!grid.ok()) Fail(2, grid.error().message);

  const maps::StructureComparison c = maps::CompareStructure(*grid, *truth, options);
  if (json) {
    std::printf("{\"precision\":%.6f,\"recall\":%.6f,\"tolerance_cells\":%d,\"observed_radius_cells\":%d,"
                "\"grid_structure\":%zu,\"grid_matched\":%zu,\"grid_outside\":%zu,"
                "\"truth_faces\":%zu,\"truth_matched\":%zu}\n",
                c.precision(), c.recall(), options.tolerance_cells, options.observed_radius_cells,
                c.grid_structure, c.grid_matched, c.grid_outside, c.truth_faces, c.truth_matched);
  } else {
    std::printf("precision: %.4f (%zu of %zu slammable cells within %d cells of true structure)\n",
                c.precision(), c.grid_matched, c.grid_structure, options.tolerance_cells);
    std::printf("recall:    %.4f (%zu of %zu observed true structure faces found)\n", c.recall(),
                c.truth_matched, c.truth_faces);
    if (c.grid_outside > 0) std::printf("outside:   %zu slammable cells beyond the truth's extent\n", c.grid_outside);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string_view(argv[1]) == "grid") return EvalGrid(argc - 2, argv + 2);
  if (argc >= 2 && (std::string_view(argv[1]) == "--help" || std::string_view(argv[1]) == "-h")) {
    std::cout << kUsage;
    return 0;
  }
  Fail(1, std::string("unknown or missing command\n") + kUsage);
}
