#include "localization/peers/mcl_run.hpp"

#include <optional>
#include <random>

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>

#include "hal/common/thread_cpu_time.hpp"
#include "hal/common/time.hpp"
#include "localization/tools/grid_run.hpp"
#include "localization/tools/odometry_poses.hpp"

namespace flat2d::localization::peers {
namespace {

double ThreadCpuMs() { return 1e3 * ThreadCpuSeconds(); }

mrpt::obs::CActionRobotMovement2D::TMotionModelOptions MotionModel(const MclOptions& o) {
  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
  model.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  // MRPT's a2 is metres of position sigma per degree turned; a3 radians per metre driven.
  model.gaussianModel = {o.xy_sigma_per_m, 0.001, o.heading_sigma_per_m, o.heading_sigma_per_rad,
                         o.min_xy_sigma_m, o.min_heading_sigma_rad};
  return model;
}

void ConfigureLikelihood(const MclOptions& o, const StructureScanOptions& scan,
                         mrpt::maps::COccupancyGridMap2D& map) {
  auto& l = map.likelihoodOptions;
  l.likelihoodMethod = mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
  l.LF_stdHit = o.hit_sigma_m;
  l.LF_maxCorrsDistance = o.max_correspondence_m;
  l.LF_maxRange = scan.max_range_m;
  l.LF_decimation = static_cast<uint32_t>(o.ray_decimation);
  l.enableLikelihoodCache = true;
}

// The particle filter over one drive: started at the first revolution, stepped at each.
class MclTracker {
 public:
  MclTracker(const MclRunOptions& options, mrpt::maps::COccupancyGridMap2D::Ptr map)
      : options_(options), motion_(MotionModel(options.mcl)), mcl_(static_cast<std::size_t>(options.mcl.particles)),
        random_(options.mcl.seed) {
    mcl_.options.metricMap = std::move(map);
    filter_.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfStandardProposal;
    filter_.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
    filter_.m_options.adaptiveSampleSize = false;
    mrpt::random::getRandomGenerator().randomize(options.mcl.seed);
  }

  // Steps the filter with this revolution; false with `failure` set when it cannot start.
  bool Step(const maps::PublishedGrid& grid, MclRunResult& result) {
    const Se2 local_T_grid = Se2Of(grid.local_T_grid);
    const double time_s = static_cast<double>(grid.start_ns) * kSecondsPerNs;
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    result.scan_returns.push_back(StructureScan(*grid.grid, options_.scan, *scan));

    const double start_ms = ThreadCpuMs();
    Se2 motion;  // zero on the first revolution
    if (!previous_) {
      if (!Start(time_s)) return false;
    } else {
      motion = previous_->Inverse() * local_T_grid;
    }
    previous_ = local_T_grid;
    mrpt::obs::CActionRobotMovement2D movement;
    movement.computeFromOdometry(mrpt::poses::CPose2D(motion.x(), motion.y(), motion.theta()), motion_);
    mrpt::obs::CActionCollection actions;
    actions.insert(movement);
    mrpt::obs::CSensoryFrame observations;
    observations.insert(scan);
    filter_.executeOn(mcl_, &actions, &observations);
    mrpt::poses::CPose2D mean;
    mcl_.getMean(mean);
    result.step_cpu_ms.push_back(ThreadCpuMs() - start_ms);
    result.estimate.push_back({time_s, Se2(mean.x(), mean.y(), mean.phi())});
    return true;
  }

  const std::optional<Error>& failure() const { return failure_; }

 private:
  // Particles drawn around the track's pose (plus the offset) at the first revolution.
  bool Start(double time_s) {
    const Result<Se2> start = InitialPoseAt(options_.initial, time_s, "first revolution");
    if (!start.ok()) {
      failure_ = start.error();
      return false;
    }
    mcl_.resetDeterministic(mrpt::math::TPose2D(start->x(), start->y(), start->theta()),
                            static_cast<std::size_t>(options_.mcl.particles));
    std::normal_distribution<double> position(0.0, options_.initial.sigma_m);
    std::normal_distribution<double> heading(0.0, options_.initial.sigma_rad);
    for (auto& particle : mcl_.m_particles) {
      particle.d.x += position(random_);
      particle.d.y += position(random_);
      particle.d.phi += heading(random_);
      particle.log_w = 0.0;
    }
    return true;
  }

  const MclRunOptions& options_;
  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motion_;
  mrpt::slam::CMonteCarloLocalization2D mcl_;
  mrpt::bayes::CParticleFilter filter_;
  std::mt19937 random_;
  std::optional<Se2> previous_;
  std::optional<Error> failure_;
};

}  // namespace

Result<MclRunResult> RunMcl(const MclRunOptions& options) {
  if (!options.initial.pose && options.initial.track.empty()) return MakeError("no initial pose given");
  if (options.mcl.particles < 1) return MakeError("the particle count must be positive");
  auto reader = maps::PriorMapReader::Open(options.map);
  if (!reader.ok()) return reader.error();
  MclRunResult result;
  const double map_start_ms = ThreadCpuMs();
  auto occupancy = OccupancyFromPriorMap(*reader, options.mcl.occupancy_resolution_m, &result.occupancy);
  if (!occupancy.ok()) return occupancy.error();
  ConfigureLikelihood(options.mcl, options.scan, **occupancy);
  result.occupancy_cpu_ms = ThreadCpuMs() - map_start_ms;

  auto poses = DeadReckonedPoses(options.dbc, options.odometry_config, options.can_log);
  if (!poses.ok()) return poses.error();
  MclTracker tracker(options, *occupancy);
  GridRunOptions grid_run;
  grid_run.capture = options.capture;
  grid_run.grid = options.grid;
  grid_run.stream = options.stream;
  grid_run.poses = std::move(*poses);
  grid_run.on_grid = [&](const maps::PublishedGrid& grid) {
    if (!grid.complete || tracker.failure()) return;
    ++result.revolutions;
    tracker.Step(grid, result);
  };
  auto run = RunGrid(grid_run);
  if (!run.ok()) return run.error();
  if (tracker.failure()) return *tracker.failure();
  if (run->unsupported) return MakeError(options.capture.string() + ": " + *run->unsupported);
  return result;
}

}  // namespace flat2d::localization::peers
