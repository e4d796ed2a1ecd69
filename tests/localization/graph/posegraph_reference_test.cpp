// The public 2D benchmarks of ../shared/data/posegraph against REFERENCE_RESULTS.md.
//
// Convention compared: SE-Sync's f (section 1a), whose certified optima f* are published
// (IJRR 2019, Table 1). We minimize exactly f (ToSeSyncProblem) with LM from the odometry
// chain and require |f - f*| <= 1e-3 f*, the published values having 4 digits (manhattan's
// f* = 6.432e3 sits 1e-4 above the 6431.39 that every local solver finds, see section 5).
// The g2o chi2 (section 1b) has no published optimum; section 5's own values are checked
// as a consistency test at the same tolerance, from the start that reaches them.
// Graphs beyond intel and CSAIL take minutes in unoptimized sanitizer builds: they run in
// optimized builds (NDEBUG) only.
#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>

#include "localization/graph/graph_costs.hpp"
#include "localization/graph/graph_file.hpp"
#include "localization/graph/graph_init.hpp"
#include "localization/graph/graph_optimizer.hpp"
#include "tests/testing/data_path.hpp"

namespace flat2d::localization::graph {
namespace {

constexpr double kRelativeTolerance = 1e-3;

struct Case {
  const char* file;
  Initialization init;
  bool sesync;            // minimize f (1a) or the g2o chi2 (1b)
  double reference;       // f* (published) or section 5's chi2 (own, unpublished)
  bool release_only;      // optimized (NDEBUG) builds only: minutes under ASan
  Solver solver = Solver::kLevenbergMarquardt;
};

// Names the case in gtest's (and so ctest's) listing instead of a byte dump.
void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

std::string Name(const ::testing::TestParamInfo<Case>& info) {
  std::string name = info.param.file;
  name = name.substr(name.find('/') + 1);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name + "_" + std::string(InitializationName(info.param.init)) +
         (info.param.sesync ? "_sesync" : "_g2o") +
         (info.param.solver == Solver::kGaussNewton ? "_gn" : "");
}

class ReferenceCostTest : public ::testing::TestWithParam<Case> {};

TEST_P(ReferenceCostTest, ReachesTheReferenceOptimum) {
  const Case& c = GetParam();
#ifndef NDEBUG
  if (c.release_only) GTEST_SKIP() << c.file << " runs in optimized (NDEBUG) builds only";
#endif
  FLAT2D_REQUIRE_DATA(path, std::string("posegraph/") + c.file);
  Result<PoseGraph> graph = ReadPoseGraphFile(path.string());
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  ASSERT_TRUE(Initialize(*graph, c.init).ok());
  PoseGraph problem = c.sesync ? ToSeSyncProblem(*graph) : *graph;
  const OptimizationResult result = Optimize(problem, {.solver = c.solver, .max_iterations = 200});
  for (std::size_t n = 0; n < graph->nodes.size(); ++n) {
    graph->nodes[n].estimate = problem.nodes[n].estimate;
  }
  const double cost = c.sesync ? SeSyncCost(*graph) : G2oChi2(*graph);
  std::printf("%s from %s, minimizing %s: %.6g (reference %.6g), %d iterations, %s, %.3f s\n",
              c.file, InitializationName(c.init).data(), c.sesync ? "SE-Sync f" : "g2o chi2", cost,
              c.reference, result.iterations, StopReasonName(result.stop_reason).data(),
              result.seconds);
  EXPECT_TRUE(result.converged()) << StopReasonName(result.stop_reason);
  EXPECT_NEAR(cost, c.reference, kRelativeTolerance * c.reference);
  // The optimizer's own cost is the convention's (no hidden factor 1/2 or weighting).
  EXPECT_NEAR(result.final_cost(), cost, 1e-9 * cost);
}

// Published f* (REFERENCE_RESULTS.md section 2), from the odometry chain.
INSTANTIATE_TEST_SUITE_P(
    SeSyncFromOdometry, ReferenceCostTest,
    ::testing::Values(Case{"g2o/intel.g2o", Initialization::kOdometry, true, 52.35, false},
                      Case{"g2o/CSAIL.g2o", Initialization::kOdometry, true, 31.70, false},
                      Case{"g2o/manhattan.g2o", Initialization::kOdometry, true, 6432.0, true},
                      Case{"toro/M3500_P_toro.graph", Initialization::kOdometry, true, 6432.0, true},
                      Case{"g2o/city10000.g2o", Initialization::kOdometry, true, 638.6, true}),
    Name);

// ais2klinik from the odometry chain: LM stalls far away (f ~ 1.5e6 after 300 iterations)
// while GN reaches f* in 9 iterations; LM reaches it from the chordal start.
INSTANTIATE_TEST_SUITE_P(
    SeSyncFromChordal, ReferenceCostTest,
    ::testing::Values(Case{"g2o/manhattan.g2o", Initialization::kChordal, true, 6432.0, true},
                      Case{"g2o/ais2klinik.g2o", Initialization::kChordal, true, 188.5, true},
                      Case{"g2o/ais2klinik.g2o", Initialization::kOdometry, true, 188.5, true,
                           Solver::kGaussNewton}),
    Name);

// Section 5's own lowest chi2 (not published), from the odometry chain except ais2klinik.
INSTANTIATE_TEST_SUITE_P(
    G2oChi2, ReferenceCostTest,
    ::testing::Values(Case{"g2o/intel.g2o", Initialization::kOdometry, false, 45.0047, false},
                      Case{"g2o/CSAIL.g2o", Initialization::kOdometry, false, 40.5551, false},
                      Case{"g2o/manhattan.g2o", Initialization::kOdometry, false, 3549.04, true},
                      Case{"g2o/manhattan.g2o", Initialization::kChordal, false, 3549.04, true},
                      Case{"g2o/city10000.g2o", Initialization::kOdometry, false, 511.985, true},
                      Case{"g2o/ais2klinik.g2o", Initialization::kChordal, false, 172.832, true}),
    Name);

}  // namespace
}  // namespace flat2d::localization::graph
