// The landmark SLAM back end (thesis 8.2) on an office-sized synthetic drive, one core:
// 3600 revolutions over 428 m of avenue, ~25 features each, 0.5 m keyframes
// (tests/localization/landmarks/synthetic_landmark_drive.hpp). Reported per revolution:
// association, factor bookkeeping and the solves (LandmarkSlamStats::backend_ms_total).
// Target 20 ms per revolution; real time is 100 ms. The drive is made outside the timing.
#include <benchmark/benchmark.h>

#include "localization/landmarks/landmark_slam.hpp"
#include "tests/localization/landmarks/synthetic_landmark_drive.hpp"

namespace {

using namespace flat2d;
using localization::landmarks::LandmarkSlam;
using localization::landmarks::LandmarkSlamOptions;
namespace synthetic = localization::landmarks::testing;

void BM_LandmarkSlamOfficeSizedDrive(benchmark::State& state) {
  const synthetic::Drive drive = synthetic::OfficeSizedDrive(8206);  // the unit test's seed
  double backend_ms = 0.0, solve_ms = 0.0, last_solve_ms = 0.0;
  int revolutions = 0;
  for (auto _ : state) {
    LandmarkSlam slam(LandmarkSlamOptions{}, drive.vehicle_T_sensor);
    for (std::size_t k = 0; k < drive.revolutions.size(); ++k) {
      const synthetic::Revolution& r = drive.revolutions[k];
      slam.Add(static_cast<TimeNs>(k) * 100 * kNsPerMs, r.odometry_world_T_vehicle, r.features);
    }
    slam.Finish();
    backend_ms += slam.stats().backend_ms_total;
    solve_ms += slam.stats().solve_ms_total;
    last_solve_ms = slam.stats().last_solve_ms;
    revolutions += slam.stats().revolutions;
  }
  state.counters["backend_ms_per_revolution"] = backend_ms / revolutions;
  state.counters["solve_ms_per_revolution"] = solve_ms / revolutions;
  state.counters["last_solve_ms"] = last_solve_ms;
}
BENCHMARK(BM_LandmarkSlamOfficeSizedDrive)->Unit(benchmark::kSecond)->Iterations(1)->Repetitions(3);

}  // namespace

BENCHMARK_MAIN();
