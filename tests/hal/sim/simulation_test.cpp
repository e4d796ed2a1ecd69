// RunSimulation end to end: determinism of the files, the merged time order, that the
// pcap, candump log and TUM truth read back with the project's own readers and agree with
// the trajectory, and the errors for bad options.
#include "hal/sim/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "hal/can/candump_log.hpp"
#include "hal/net/datagram_source.hpp"
#include "hal/sim/simulation_sinks.hpp"
#include "hal/velodyne/velodyne_stream.hpp"
#include "tests/hal/sim/simulation_test_support.hpp"

namespace flat2d::hal::sim {
namespace {

using testing::ReadBytes;
using testing::ScratchDir;
using testing::ShortRun;

Result<SimulationSummary> SimulateInto(const SimulationOptions& options,
                                       const std::filesystem::path& directory) {
  auto files = FileSink::Open(directory);
  if (!files.ok()) return files.error();
  SimulationSink* sinks[] = {&*files};
  return RunSimulation(options, sinks);
}

// Records the time of every event, by kind, in arrival order.
class TimelineSink final : public SimulationSink {
 public:
  Status OnDatagram(const net::UdpDatagram& datagram) override {
    times_.push_back(datagram.receive_time_ns);
    return Status::Ok();
  }
  Status OnCanFrame(const can::CanFrame& frame) override {
    times_.push_back(frame.time_ns);
    return Status::Ok();
  }
  Status OnTruthPose(TimeNs time_ns, const VehicleState&) override {
    times_.push_back(time_ns);
    return Status::Ok();
  }
  const std::vector<TimeNs>& times() const { return times_; }

 private:
  std::vector<TimeNs> times_;
};

TEST(Simulation, SameOptionsGiveByteIdenticalFiles) {
  ScratchDir first("same_a"), second("same_b");
  const SimulationOptions options = ShortRun(0.5);
  ASSERT_TRUE(SimulateInto(options, first.path()).ok());
  ASSERT_TRUE(SimulateInto(options, second.path()).ok());
  for (const char* name : {kLidarFile, kCanFile, kTruthFile, kDbcFile, "truth_map.pgm", "truth_map.yaml"}) {
    const std::string a = ReadBytes(first.path() / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_TRUE(a == ReadBytes(second.path() / name)) << name << " differs between equal runs";
  }
}

TEST(Simulation, OtherSeedChangesSensorsButNotTruth) {
  ScratchDir first("seed_a"), second("seed_b");
  SimulationOptions options = ShortRun(0.5);
  ASSERT_TRUE(SimulateInto(options, first.path()).ok());
  options.seed = 8;
  ASSERT_TRUE(SimulateInto(options, second.path()).ok());
  EXPECT_NE(ReadBytes(first.path() / kLidarFile), ReadBytes(second.path() / kLidarFile));
  EXPECT_NE(ReadBytes(first.path() / kCanFile), ReadBytes(second.path() / kCanFile));
  // The vehicle's motion is the world's, not the sensors': truth does not depend on the seed.
  EXPECT_EQ(ReadBytes(first.path() / kTruthFile), ReadBytes(second.path() / kTruthFile));
}

TEST(Simulation, EventsArriveInTimeOrderWithinTheDuration) {
  const SimulationOptions options = ShortRun(0.5);
  TimelineSink timeline;
  SimulationSink* sinks[] = {&timeline};
  auto summary = RunSimulation(options, sinks);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  const std::vector<TimeNs>& times = timeline.times();
  EXPECT_EQ(times.size(), summary->data_packets + summary->position_packets + summary->can_frames +
                              summary->truth_poses);
  EXPECT_TRUE(std::is_sorted(times.begin(), times.end()));
  EXPECT_GE(times.front(), options.start_epoch_ns);
  EXPECT_LE(times.back(), options.start_epoch_ns + 500'000'000);
}

TEST(Simulation, PcapDecodesWithTheVelodyneStream) {
  ScratchDir out("pcap");
  const SimulationOptions options = ShortRun(1.0);
  auto summary = SimulateInto(options, out.path());
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  auto capture = net::OpenCapture(out.path() / kLidarFile);
  ASSERT_TRUE(capture.ok()) << capture.error().message;

  velodyne::VelodyneStream stream({}, [](const velodyne::Revolution&) {});
  TimeNs previous_ns = 0;
  std::uint64_t datagrams = 0;
  while (auto datagram = (*capture)->Next()) {
    EXPECT_GE(datagram->receive_time_ns, previous_ns);
    previous_ns = datagram->receive_time_ns;
    EXPECT_EQ(datagram->source.address, kVelodyneDefaultAddress);
    EXPECT_EQ(datagram->destination.address, net::kIpv4Broadcast);
    stream.Push(*datagram);
    ++datagrams;
  }
  stream.Finish();
  const velodyne::VelodyneStreamStats& stats = stream.stats();
  EXPECT_EQ(datagrams, summary->data_packets + summary->position_packets);
  EXPECT_EQ((*capture)->stats().malformed, 0u);
  EXPECT_EQ(stats.data_packets, summary->data_packets);
  EXPECT_EQ(stats.position_packets, summary->position_packets);
  EXPECT_EQ(stats.malformed, 0u);
  EXPECT_EQ(stats.lost_packets, 0u);
  EXPECT_EQ(stats.out_of_order, 0u);
  ASSERT_TRUE(stream.identification().has_value());
  EXPECT_EQ(stream.identification()->model, velodyne::Model::kVlp16);
  // A VLP-16 data packet spans 1.327 ms: 754 packets and 10 revolutions in a second.
  EXPECT_NEAR(static_cast<double>(summary->data_packets), 1.0 / 1.327e-3, 2.0);
  // Ten turns; the first and the last may be cut at the ends of the run (partial).
  EXPECT_GE(stats.revolutions + 2, 10u);
  EXPECT_LE(stats.revolutions, 10u);
  EXPECT_GT(stats.points, summary->data_packets * 100);  // the yard's walls are in range
}

TEST(Simulation, CanLogReadsBackInOrderAtTheConfiguredRates) {
  ScratchDir out("can");
  const SimulationOptions options = ShortRun(1.0);
  auto summary = SimulateInto(options, out.path());
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  auto reader = can::CandumpReader::Open(out.path() / kCanFile);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  can::CanFrame frame;
  TimeNs previous_ns = 0;
  std::uint64_t frames = 0;
  while (reader->Next(frame)) {
    EXPECT_GE(frame.time_ns, previous_ns);
    previous_ns = frame.time_ns;
    EXPECT_EQ(frame.interface_name(), "can0");
    ++frames;
  }
  EXPECT_EQ(reader->stats().malformed, 0u);
  EXPECT_EQ(frames, summary->can_frames);
  // WHEEL_SPEEDS and YAW_RATE at 100 Hz, STEERING at 50 Hz (odometry_simulator.hpp):
  // 250 frames a second, within one frame per message at the ends. candump keeps
  // microseconds, so compare with the run's own count rather than exact times.
  EXPECT_NEAR(static_cast<double>(frames), 1.0 * 250.0, 3.0);
}

TEST(Simulation, TruthTumIsTheTrajectoryAtTheTruthRate) {
  ScratchDir out("truth");
  SimulationOptions options = ShortRun(1.0);
  options.truth_rate_hz = 100.0;
  auto summary = SimulateInto(options, out.path());
  ASSERT_TRUE(summary.ok()) << summary.error().message;

  auto scene = Scene::Create(std::get<SceneDescription>(options.world));
  ASSERT_TRUE(scene.ok());
  auto trajectory = Trajectory::Create(*scene, std::get<SceneDescription>(options.world).drives(0));
  ASSERT_TRUE(trajectory.ok());
  std::vector<TimeNs> times;
  for (const std::string& line : testing::SplitLines(ReadBytes(out.path() / kTruthFile))) {
    long long seconds = 0, nanoseconds = 0;
    double x, y, z, qx, qy, qz, qw;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lld.%9lld %lf %lf %lf %lf %lf %lf %lf", &seconds,
                          &nanoseconds, &x, &y, &z, &qx, &qy, &qz, &qw), 9) << line;
    const TimeNs time_ns = seconds * kNsPerSecond + nanoseconds;
    const double drive_time_s = static_cast<double>(time_ns - options.start_epoch_ns) * 1e-9;
    const Eigen::Isometry3d truth = trajectory->At(drive_time_s).world_T_vehicle;
    // Written with 9 decimals: equal to the trajectory within rounding (5e-10), so 1e-8.
    EXPECT_LT((truth.translation() - Eigen::Vector3d(x, y, z)).norm(), 1e-8) << line;
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    EXPECT_NEAR(q.norm(), 1.0, 1e-8);
    EXPECT_LT(q.angularDistance(Eigen::Quaterniond(truth.rotation())), 1e-8) << line;
    times.push_back(time_ns);
  }
  ASSERT_EQ(times.size(), summary->truth_poses);
  ASSERT_EQ(times.size(), 101u);  // 0, 0.01, ..., 1.00 s
  EXPECT_EQ(times.front(), options.start_epoch_ns);
  for (std::size_t i = 1; i < times.size(); ++i) {
    EXPECT_EQ(times[i] - times[i - 1], 10'000'000);  // 100 Hz exactly, no drift
  }
  // The vehicle moved: the truth is not a constant.
  EXPECT_GT(trajectory->At(1.0).world_T_vehicle.translation().norm(), 0.1);
}

TEST(Simulation, BadOptionsAreErrorsThatSayWhatIsAllowed) {
  const std::span<SimulationSink* const> none;
  SimulationOptions options = ShortRun();
  options.drive = 3;
  auto result = RunSimulation(options, none);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("has 1 drive"), std::string::npos) << result.error().message;

  options = ShortRun();
  options.truth_rate_hz = 50.0;
  result = RunSimulation(options, none);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("truth rate"), std::string::npos) << result.error().message;

  options = ShortRun();
  options.duration_s = -1.0;
  EXPECT_FALSE(RunSimulation(options, none).ok());

  options = ShortRun();
  options.lidar.rotation_hz = 25.0;
  EXPECT_FALSE(RunSimulation(options, none).ok());

  options = ShortRun();
  options.world = std::string("no-such-world");
  result = RunSimulation(options, none);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("campus"), std::string::npos) << result.error().message;
}

TEST(Simulation, UnwritableOutputDirectoryFailsBeforeSimulating) {
  ScratchDir scratch("unwritable");
  std::filesystem::create_directories(scratch.path());
  std::FILE* file = std::fopen((scratch.path() / "file").c_str(), "wb");
  ASSERT_NE(file, nullptr);
  std::fclose(file);
  auto sink = FileSink::Open(scratch.path() / "file" / "out");
  ASSERT_FALSE(sink.ok());
  EXPECT_NE(sink.error().message.find("file/out"), std::string::npos) << sink.error().message;
}

TEST(Simulation, BuiltInWorldsResolveAndTheirDrivesDescribe) {
  for (const char* name : {"office", "campus", "ramps", "occluders"}) {
    auto world = ResolveWorld(name);
    ASSERT_TRUE(world.ok()) << name << ": " << world.error().message;
    auto drives = DescribeDrives(*world);
    ASSERT_TRUE(drives.ok()) << name << ": " << drives.error().message;
    ASSERT_GE(drives->size(), 2u) << name << ": a mapping drive and a localization drive";
    for (const DriveInfo& drive : *drives) {
      EXPECT_GT(drive.duration_s, 0.0) << name << " " << drive.name;
      // A drive covers ground at no more than its top speed.
      EXPECT_GT(drive.length_m, 0.0) << name << " " << drive.name;
      EXPECT_LE(drive.length_m, drive.duration_s * world->drives(drive.index).speed_mps() * 1.01)
          << name << " " << drive.name;
    }
  }
}

}  // namespace
}  // namespace flat2d::hal::sim
