// The public SE(3) benchmarks of ../shared/data/posegraph against REFERENCE_RESULTS.md
// section 2 (SE-Sync IJRR 2019, Table 2): sphere 1.687e3, torus 2.423e4, garage 1.263e0,
// cubicle 7.171e2, the certified optima of SE-Sync's f (section 1a).
//
// We minimize exactly f (ToSeSyncProblem) with LM and require f rounded to 4 significant
// digits to equal the published value. Starts: the file's vertices for sphere, garage and
// cubicle; the chordal initialization for torus, whose file vertices lead LM to a local
// minimum (f = 5.275e4); cubicle also from the chordal start. Each case takes 0.3-2.5 s in a
// release build and about six times that under the sanitizers, where cubicle from its file
// (15 s there, the same optimum as from the chordal start) is left out.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "localization/graph/g2o_se3_io.hpp"
#include "localization/graph/se3_costs.hpp"
#include "localization/graph/se3_graph_optimizer.hpp"
#include "localization/graph/se3_init.hpp"
#include "tests/testing/data_path.hpp"
#include "tests/testing/sanitizer.hpp"

namespace flat2d::localization::graph {
namespace {

using flat2d::testing::kSanitized;

struct Case {
  const char* file;
  Initialization init;
  double published;             // f*, 4 significant digits
  bool unsanitized_only = false;  // a repeat left out of the slow sanitizer builds
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file << " from " << InitializationName(c.init); }

std::string Name(const ::testing::TestParamInfo<Case>& info) {
  std::string name = info.param.file;
  name = name.substr(name.find('/') + 1);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name + "_" + std::string(InitializationName(info.param.init));
}

// `value` rounded to `digits` significant digits.
double RoundToSignificant(double value, int digits) {
  const double scale = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(value)))));
  return std::round(value * scale) / scale;
}

class Se3ReferenceTest : public ::testing::TestWithParam<Case> {};

TEST_P(Se3ReferenceTest, ReachesThePublishedSeSyncOptimum) {
  const Case& c = GetParam();
  if (kSanitized && c.unsanitized_only) GTEST_SKIP() << c.file << " from its file: unsanitized builds only";
  FLAT2D_REQUIRE_DATA(path, std::string("posegraph/") + c.file);
  Result<Se3PoseGraph> graph = ReadG2oSe3File(path.string());
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  ASSERT_TRUE(Initialize(*graph, c.init).ok());
  Se3PoseGraph problem = ToSeSyncProblem(*graph);
  const OptimizationResult result = Optimize(problem, {.max_iterations = 100});
  for (std::size_t n = 0; n < graph->nodes.size(); ++n) {
    graph->nodes[n].estimate = problem.nodes[n].estimate;
  }
  const double f = SeSyncCost(*graph);
  std::printf("%s from %s: SE-Sync f %.7g (published %.4g), %d iterations, %s, %.3f s\n", c.file,
              InitializationName(c.init).data(), f, c.published, result.iterations,
              StopReasonName(result.stop_reason).data(), result.seconds);
  EXPECT_TRUE(result.converged()) << StopReasonName(result.stop_reason);
  EXPECT_NEAR(RoundToSignificant(f, 4), c.published, 1e-9 * c.published) << "f = " << f;
  // The optimizer's own cost is f (no hidden factor 1/2 or weighting).
  EXPECT_NEAR(result.final_cost(), f, 1e-9 * f);
}

// REFERENCE_RESULTS.md section 2, Table 2 of the IJRR paper.
INSTANTIATE_TEST_SUITE_P(
    SeSync, Se3ReferenceTest,
    ::testing::Values(Case{"g2o/sphere2500.g2o", Initialization::kFile, 1.687e3},
                      Case{"g2o/torus3D.g2o", Initialization::kChordal, 2.423e4},
                      Case{"g2o/parking-garage.g2o", Initialization::kFile, 1.263e0},
                      Case{"g2o/cubicle.g2o", Initialization::kFile, 7.171e2, true},
                      Case{"g2o/cubicle.g2o", Initialization::kChordal, 7.171e2}),
    Name);

}  // namespace
}  // namespace flat2d::localization::graph
