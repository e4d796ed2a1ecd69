#include "localization/tools/features_run.hpp"

#include <map>
#include <memory>

#include "hal/cloud/kitti_bin_file.hpp"
#include "hal/cloud/pcd_file.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/sim/scene_landmarks.hpp"
#include "localization/evaluation/trajectory_error_3d.hpp"
#include "localization/tools/revolution_cloud.hpp"
#include "maps/features3d/feature_options.hpp"
#include "maps/range3d/range_frame.hpp"

namespace flat2d::localization::tools {
namespace {

using maps::range3d::SensorModel;

// Truth poses are 200 Hz; a revolution's fans need the truth at their own times.
constexpr TimeNs kTruthMaxGapNs = 100 * kNsPerMs;
// Faces and poles lower than this make no landmark (curbs, benches, desks).
constexpr double kMinLandmarkHeightM = 1.0;

// One extractor per sensor model seen (a capture has one; the map keeps the code simple).
class Extractors {
 public:
  explicit Extractors(const maps::features3d::FeatureExtractionOptions& options) : options_(options) {}
  maps::features3d::FeatureExtractor& For(SensorModel sensor) {
    auto it = extractors_.find(sensor);
    if (it == extractors_.end()) {
      it = extractors_.emplace(sensor, std::make_unique<maps::features3d::FeatureExtractor>(
                                          maps::features3d::ProjectionForSensor(options_, sensor),
                                          maps::features3d::OptionsForSensor(options_, sensor))).first;
    }
    return *it->second;
  }

 private:
  const maps::features3d::FeatureExtractionOptions& options_;
  std::map<SensorModel, std::unique_ptr<maps::features3d::FeatureExtractor>> extractors_;
};

// The judge of a simulator run: the world's landmarks and the truth.
class Judge {
 public:
  explicit Judge(const FeaturesRunOptions& options)
      : options_(options), landmarks_(hal::sim::StaticLandmarks(*options.world, kMinLandmarkHeightM)) {}

  Result<evaluation::RevolutionAccuracy> Evaluate(TimeNs stamp, const maps::features3d::FeatureSet& features,
                                                  const std::vector<Eigen::Vector3f>& points) const {
    const auto world_T_vehicle = evaluation::InterpolatedPose(options_.truth, stamp, kTruthMaxGapNs);
    if (!world_T_vehicle) return MakeError("the truth does not cover the revolution at " + std::to_string(stamp) + " ns");
    const double world_time_s = static_cast<double>(stamp - options_.truth.front().time_ns) * 1e-9 + options_.world_time_offset_s;
    return evaluation::EvaluateFeatures(features, points, *world_T_vehicle * options_.vehicle_T_sensor, landmarks_,
                                        hal::sim::MoversAt(*options_.world, world_time_s), options_.accuracy);
  }

  // reference_T_sensor(t) by the truth, for deskewing.
  SensorMotion Motion(TimeNs reference_ns) const {
    return [this, reference_ns](TimeNs t) {
      const auto a = evaluation::InterpolatedPose(options_.truth, reference_ns, kTruthMaxGapNs);
      const auto b = evaluation::InterpolatedPose(options_.truth, t, kTruthMaxGapNs);
      if (!a || !b) return Eigen::Isometry3d::Identity();
      return options_.vehicle_T_sensor.inverse() * a->inverse() * *b * options_.vehicle_T_sensor;
    };
  }

 private:
  const FeaturesRunOptions& options_;
  const hal::sim::SceneLandmarks landmarks_;
};

// Extracts and judges one revolution's cloud and hands it on; false on a truth error.
class CaptureFeatures {
 public:
  CaptureFeatures(const FeaturesRunOptions& options, const FeaturesHandler& handler)
      : handler_(handler), extractors_(options.extraction),
        up_((options.vehicle_T_sensor.linear().transpose() * Eigen::Vector3d::UnitZ()).cast<float>()) {
    if (options.world) judge_.emplace(options);
  }

  hal::cloud::PointCloud Cloud(const hal::velodyne::Revolution& revolution) const {
    return RevolutionCloud(revolution, judge_ ? judge_->Motion(revolution.start_ns()) : SensorMotion{});
  }

  Status Process(int index, TimeNs stamp, SensorModel sensor, const hal::cloud::PointCloud& cloud) {
    maps::features3d::FeatureExtractor& extractor = extractors_.For(sensor);
    RevolutionFeatures out{index, stamp, std::string(maps::range3d::SensorModelName(sensor)),
                           &extractor.Extract(cloud.points, up_), &extractor, std::nullopt};
    if (judge_) {
      auto accuracy = judge_->Evaluate(stamp, *out.features, cloud.points);
      if (!accuracy.ok()) return accuracy.error();
      out.accuracy = std::move(*accuracy);
    }
    handler_(out);
    return Status::Ok();
  }

 private:
  const FeaturesHandler& handler_;
  Extractors extractors_;
  const Eigen::Vector3f up_;
  std::optional<Judge> judge_;
};

// The largest partial revolution of a capture too short for a complete one (the snippets of
// driver test suites), so that every capture yields features.
struct PartialRevolution {
  TimeNs stamp = 0;
  SensorModel sensor = SensorModel::kAuto;
  hal::cloud::PointCloud cloud;
};

Status RunCapture(const FeaturesRunOptions& options, const FeaturesHandler& handler) {
  auto source = hal::net::OpenCapture(options.input);
  if (!source.ok()) return source.error();
  CaptureFeatures features(options, handler);
  hal::velodyne::VelodyneStream* stream = nullptr;
  int index = 0;
  Status status = Status::Ok();
  std::optional<PartialRevolution> partial;
  auto on_revolution = [&](const hal::velodyne::Revolution& revolution) {
    if (!status.ok()) return;
    const SensorModel sensor = maps::range3d::SensorModelOf(stream->identification()->model);
    if (!revolution.complete) {
      if (index == 0 && (!partial || static_cast<std::size_t>(revolution.points) > partial->cloud.points.size())) {
        partial = PartialRevolution{revolution.start_ns(), sensor, features.Cloud(revolution)};
      }
      return;
    }
    const int current = index++;
    if (options.revolution >= 0 && current != options.revolution) return;
    status = features.Process(current, revolution.start_ns(), sensor, features.Cloud(revolution));
  };
  hal::velodyne::VelodyneStream velodyne(options.stream, on_revolution);
  stream = &velodyne;
  while (auto datagram = (*source)->Next()) velodyne.Push(*datagram);
  velodyne.Finish();
  if (velodyne.model_error()) return MakeError(options.input.string() + ": " + velodyne.model_error()->message);
  if (!status.ok()) return MakeError(options.input.string() + ": " + status.error().message);
  if (index == 0 && partial && options.revolution <= 0) {
    return features.Process(0, partial->stamp, partial->sensor, partial->cloud);
  }
  if (index == 0) return MakeError(options.input.string() + ": no Velodyne revolution");
  if (options.revolution >= index) {
    return MakeError(options.input.string() + ": --revolution " + std::to_string(options.revolution) + " but only " +
                     std::to_string(index) + " complete revolutions");
  }
  return Status::Ok();
}

Status RunCloudFile(const FeaturesRunOptions& options, const FeaturesHandler& handler) {
  const std::string extension = options.input.extension().string();
  auto cloud = extension == ".bin" ? hal::cloud::ReadKittiBin(options.input) : hal::cloud::ReadPcd(options.input);
  if (!cloud.ok()) return cloud.error();
  SensorModel sensor = maps::range3d::DetectLidar(cloud->points);
  if (sensor == SensorModel::kUnorganized) {
    if (extension != ".bin") return MakeError(options.input.string() + ": the points match no Velodyne laser table");
    sensor = SensorModel::kKitti64;
  }
  Extractors extractors(options.extraction);
  maps::features3d::FeatureExtractor& extractor = extractors.For(sensor);
  const RevolutionFeatures out{0, 0, std::string(maps::range3d::SensorModelName(sensor)),
                               &extractor.Extract(cloud->points, Eigen::Vector3f::UnitZ()), &extractor, std::nullopt};
  handler(out);
  return Status::Ok();
}

}  // namespace

Status RunFeatures(const FeaturesRunOptions& options, const FeaturesHandler& handler) {
  const std::string extension = options.input.extension().string();
  if (extension == ".pcd" || extension == ".bin") {
    if (options.world) return MakeError("judging against a world needs a simulator capture, not " + options.input.string());
    return RunCloudFile(options, handler);
  }
  if (options.world && options.truth.size() < 2) return MakeError("judging against a world needs its truth trajectory");
  return RunCapture(options, handler);
}

}  // namespace flat2d::localization::tools
