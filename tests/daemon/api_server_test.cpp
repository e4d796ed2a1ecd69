// The API server and the client library against each other over a real Unix socket
// (daemon/service/api_server.hpp, daemon/client/client.hpp): answers composed from the pose
// board, errors for bad requests that leave other clients alone, a slow subscriber that
// gets the newest pose and no queue, a full client table, 50 concurrent clients, and a
// client that reconnects when the server comes back.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <thread>
#include <vector>

#include "daemon/api/delimited_frames.hpp"
#include "daemon/client/client.hpp"
#include "daemon/service/api_server.hpp"

namespace flat2d::daemon {
namespace {

namespace v1 = api::v1;
using localization::Se2;

constexpr TimeNs kStart = 1767225600LL * kNsPerSecond;
constexpr TimeNs kStep = 10 * kNsPerMs;
const Se2 kNodePose(100.0, 50.0, 0.5);
constexpr TimeNs kNodeNs = kStart + kNsPerSecond;

// A board with 2 s of odometry at 1 m/s straight ahead and a fix at t = 1 s.
std::unique_ptr<PoseBoard> MakeBoard() {
  auto board = PoseBoard::Create({.capacity = 512});
  EXPECT_TRUE(board.ok());
  auto owned = std::make_unique<PoseBoard>(std::move(*board));
  for (int k = 0; k <= 200; ++k) {
    localization::OdometrySample sample;
    sample.time_ns = kStart + k * kStep;
    sample.local_T_vehicle = Se2(0.01 * k, 0.0, 0.0);
    sample.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal() * (k + 1);
    sample.step_covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
    owned->PushOdometry(sample);
  }
  owned->PublishFix({.has_fix = true,
                     .node_ns = kNodeNs,
                     .node_pose = kNodePose,
                     .node_covariance = Eigen::Vector3d(0.01, 0.01, 1e-4).asDiagonal(),
                     .global_T_local = kNodePose * Se2(1.0, 0.0, 0.0).Inverse(),
                     .state = localization::LocalizerState::kLocalized,
                     .last_accepted_ns = kNodeNs});
  return owned;
}

class ApiServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    socket_path_ = (std::filesystem::temp_directory_path() / ("flat2d_api_" + std::to_string(::getpid()) + ".sock")).string();
    board_ = MakeBoard();
    MapSummary map{.path = "/var/lib/flat2d/map.f2m", .resolution_m = 0.05, .tiles = 15, .file_bytes = 21228};
    handler_ = std::make_unique<ApiHandler>(
        *board_, map, InitialPoseDefaults{0.5, 0.05},
        [this](const InitialPoseRequest& request) {
          last_pose_ = request;
          ++poses_set_;
        },
        [] {
          ServiceFigures figures;
          figures.lidar_rate_hz = 1808.0;
          figures.clients = 3;
          return figures;
        });
    StartServer();
  }
  void TearDown() override {
    StopServer();
    std::filesystem::remove(socket_path_);
  }
  void StartServer(std::size_t max_clients = 64) {
    auto listener = ListenUnix(socket_path_, 0660);
    ASSERT_TRUE(listener.ok()) << listener.error().message;
    std::vector<hal::net::SocketFd> listeners;
    listeners.push_back(std::move(*listener));
    auto server = ApiServer::Create({.max_clients = max_clients, .max_message_bytes = 4096, .max_subscribe_hz = 100.0},
                                    std::move(listeners), *handler_);
    ASSERT_TRUE(server.ok()) << server.error().message;
    server_ = std::move(*server);
    thread_ = std::jthread([this](std::stop_token stop) { server_->Run(stop); });
  }
  void StopServer() {
    if (!server_) return;
    thread_.request_stop();
    thread_ = {};
    server_.reset();
  }
  client::Client MakeClient(int reconnect_ms = 0) {
    return client::Client({.endpoint = socket_path_, .timeout_ms = 2000, .reconnect_ms = reconnect_ms});
  }
  int Connect() {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::strncpy(address.sun_path, socket_path_.c_str(), sizeof(address.sun_path) - 1);
    EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
    return fd;
  }
  static void SendBytes(int fd, const std::vector<std::uint8_t>& bytes) {
    ASSERT_EQ(::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bytes.size()));
  }
  static std::vector<std::uint8_t> Framed(const v1::Request& request) {
    std::vector<std::uint8_t> bytes(request.ByteSizeLong() + 5);
    bytes.resize(*wire::AppendDelimited(request, 4096, bytes, 0));
    return bytes;
  }
  // One response read from a raw socket; nullopt at end of stream.
  static std::optional<v1::Response> ReadResponse(int fd, wire::FrameReader& reader) {
    while (true) {
      if (reader.Next() == wire::FrameStatus::kFrame) {
        v1::Response response;
        EXPECT_TRUE(response.ParseFromArray(reader.frame().data(), static_cast<int>(reader.frame().size())));
        return response;
      }
      const auto space = reader.WritableSpace();
      const ssize_t n = ::recv(fd, space.data(), space.size(), 0);
      if (n <= 0) return std::nullopt;
      reader.Commit(static_cast<std::size_t>(n));
    }
  }

  std::string socket_path_;
  std::unique_ptr<PoseBoard> board_;
  std::unique_ptr<ApiHandler> handler_;
  std::unique_ptr<ApiServer> server_;
  std::jthread thread_;
  std::optional<InitialPoseRequest> last_pose_;
  std::atomic<int> poses_set_{0};
};

TEST_F(ApiServerTest, PosesAreTheNodeComposedWithOdometry) {
  client::Client client = MakeClient();
  const TimeNs at = kNodeNs + 500 * kNsPerMs;  // 0.5 m past the node
  auto pose = client.PoseAt(at);
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  EXPECT_TRUE(pose->valid());
  EXPECT_EQ(pose->time_ns(), at);
  EXPECT_NEAR(pose->global_t_vehicle().x(), 100.0 + 0.5 * std::cos(0.5), 1e-9);
  EXPECT_NEAR(pose->global_t_vehicle().y(), 50.0 + 0.5 * std::sin(0.5), 1e-9);
  EXPECT_NEAR(pose->global_t_vehicle().theta(), 0.5, 1e-12);
  EXPECT_EQ(pose->state(), v1::LOCALIZED);
  EXPECT_NEAR(pose->since_accepted_match_s(), 0.5, 1e-9);
  ASSERT_EQ(pose->covariance_size(), 9);
  EXPECT_GT(pose->covariance(0), 0.01);  // the node's 0.01 plus the odometry's growth
  EXPECT_NEAR(pose->global_t_local().x(), (kNodePose * Se2(1.0, 0.0, 0.0).Inverse()).translation().x(), 1e-12);

  auto now = client.PoseNow();
  ASSERT_TRUE(now.ok()) << now.error().message;
  EXPECT_EQ(now->time_ns(), kStart + 200 * kStep);  // the newest odometry sample
  EXPECT_NEAR(now->global_t_vehicle().x(), 100.0 + std::cos(0.5), 1e-9);
}

TEST_F(ApiServerTest, PoseAtOutsideTheWindowIsAClearError) {
  client::Client client = MakeClient();
  auto early = client.PoseAt(kStart - 3 * kNsPerSecond);
  ASSERT_FALSE(early.ok());
  EXPECT_NE(early.error().message.find("OUT_OF_WINDOW"), std::string::npos) << early.error().message;
  EXPECT_NE(early.error().message.find("3.000000 s before"), std::string::npos) << early.error().message;
  auto late = client.PoseAt(kStart + 10 * kNsPerSecond);
  ASSERT_FALSE(late.ok());
  EXPECT_NE(late.error().message.find("after"), std::string::npos) << late.error().message;
}

TEST_F(ApiServerTest, SetInitialPoseReachesTheLocalizerAndBadArgumentsDoNot) {
  client::Client client = MakeClient();
  ASSERT_TRUE(client.SetInitialPose(12.0, -3.0, 1.25).ok());
  ASSERT_EQ(poses_set_, 1);
  EXPECT_NEAR(last_pose_->global_T_vehicle.translation().x(), 12.0, 1e-12);
  EXPECT_NEAR(last_pose_->covariance(0, 0), 0.25, 1e-12);   // the configured default sigma 0.5 m
  EXPECT_NEAR(last_pose_->covariance(2, 2), 0.0025, 1e-12);
  ASSERT_TRUE(client.SetInitialPose(1.0, 2.0, 3.0, 0.1, 0.01).ok());
  EXPECT_NEAR(last_pose_->covariance(1, 1), 0.01, 1e-12);
  const Status nan = client.SetInitialPose(std::nan(""), 0.0, 0.0);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().message.find("INVALID_ARGUMENT"), std::string::npos);
  EXPECT_FALSE(client.SetInitialPose(0.0, 0.0, 0.0, -1.0).ok());
  EXPECT_EQ(poses_set_, 2);
}

TEST_F(ApiServerTest, StatusAndMapInfo) {
  client::Client client = MakeClient();
  auto status = client.GetStatus();
  ASSERT_TRUE(status.ok()) << status.error().message;
  EXPECT_EQ(status->state(), v1::LOCALIZED);
  EXPECT_DOUBLE_EQ(status->lidar().rate_hz(), 1808.0);
  EXPECT_EQ(status->clients(), 3u);
  auto map = client.GetMapInfo();
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->path(), "/var/lib/flat2d/map.f2m");
  EXPECT_EQ(map->tiles(), 15u);
}

TEST_F(ApiServerTest, AnUnparsableRequestGetsAnErrorAndTheConnectionStays) {
  const int fd = Connect();
  wire::FrameReader reader(4096);
  SendBytes(fd, {0x04, 0xFF, 0xFF, 0xFF, 0xFF});  // a 4-byte frame that is no Request
  auto error = ReadResponse(fd, reader);
  ASSERT_TRUE(error.has_value());
  ASSERT_TRUE(error->has_error());
  EXPECT_EQ(error->error().code(), v1::Error::MALFORMED);
  SendBytes(fd, {0x02, 0x08, 0x05});  // id 5, no kind
  auto empty = ReadResponse(fd, reader);
  ASSERT_TRUE(empty.has_value() && empty->has_error());
  v1::Request request;
  request.set_id(77);
  request.mutable_pose_now();
  SendBytes(fd, Framed(request));
  auto pose = ReadResponse(fd, reader);
  ASSERT_TRUE(pose.has_value());
  EXPECT_EQ(pose->id(), 77u);
  EXPECT_TRUE(pose->has_pose());
  EXPECT_EQ(server_->stats().malformed_requests, 2u);
  ::close(fd);
}

TEST_F(ApiServerTest, AnOversizedRequestClosesOnlyItsOwnConnection) {
  client::Client bystander = MakeClient();
  ASSERT_TRUE(bystander.PoseNow().ok());
  const int fd = Connect();
  SendBytes(fd, {0x80, 0x80, 0x40});  // 1 MiB announced, above 4096
  wire::FrameReader reader(4096);
  auto error = ReadResponse(fd, reader);
  ASSERT_TRUE(error.has_value() && error->has_error());
  EXPECT_FALSE(ReadResponse(fd, reader).has_value());  // then closed
  ::close(fd);
  EXPECT_TRUE(bystander.PoseNow().ok());
  EXPECT_EQ(bystander.reconnects(), 0u);
}

TEST_F(ApiServerTest, ASlowSubscriberGetsTheNewestPoseAndNoQueue) {
  const int slow = Connect();
  v1::Request subscribe;
  subscribe.set_id(9);
  subscribe.mutable_subscribe()->set_rate_hz(1000.0);  // clamped to 100 Hz
  SendBytes(slow, Framed(subscribe));
  client::Client other = MakeClient();
  // Until the kernel's bounded buffer towards `slow` is full (~100 updates), the other
  // client is served while `slow` reads nothing.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (server_->stats().updates_skipped == 0 && std::chrono::steady_clock::now() < give_up) {
    ASSERT_TRUE(other.PoseNow().ok());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GT(server_->stats().updates_skipped, 0u);
  EXPECT_EQ(server_->stats().slow_disconnects, 0u);
  // The board moves on; what the slow subscriber reads next ends in the new pose.
  localization::OdometrySample sample;
  sample.time_ns = kStart + 250 * kStep;
  sample.local_T_vehicle = Se2(2.5, 0.0, 0.0);
  board_->PushOdometry(sample);
  wire::FrameReader reader(4096);
  std::int64_t newest = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (newest != sample.time_ns && std::chrono::steady_clock::now() < deadline) {
    auto update = ReadResponse(slow, reader);
    ASSERT_TRUE(update.has_value());
    if (update->has_pose()) newest = update->pose().time_ns();
  }
  EXPECT_EQ(newest, sample.time_ns);
  ::close(slow);
}

TEST_F(ApiServerTest, AFullClientTableRefusesNewConnections) {
  StopServer();
  StartServer(4);
  std::vector<client::Client> clients;
  for (int i = 0; i < 4; ++i) {
    clients.push_back(MakeClient());
    ASSERT_TRUE(clients.back().PoseNow().ok());
  }
  client::Client fifth = MakeClient();
  EXPECT_FALSE(fifth.PoseNow().ok());
  EXPECT_GE(server_->stats().refused, 1u);
  clients.pop_back();  // a slot frees
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  client::Client sixth = MakeClient();
  EXPECT_TRUE(sixth.PoseNow().ok());
}

TEST_F(ApiServerTest, FiftyConcurrentClients) {
  std::atomic<int> failures{0};
  std::vector<std::jthread> threads;
  for (int t = 0; t < 50; ++t) {
    threads.emplace_back([&, t] {
      client::Client client = MakeClient();
      for (int i = 0; i < 100; ++i) {
        auto pose = client.PoseAt(kStart + (t + i) * kStep);
        if (!pose.ok() || pose->time_ns() != kStart + (t + i) * kStep) ++failures;
      }
    });
  }
  threads.clear();
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(server_->stats().requests, 5000u);
}

TEST_F(ApiServerTest, TheClientReconnectsWhenTheServerComesBack) {
  client::Client client = MakeClient(3000);
  ASSERT_TRUE(client.PoseNow().ok());
  StopServer();
  std::thread restart([this] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    StartServer();
  });
  auto pose = client.PoseNow();  // fails on the old connection, then retries until the server is back
  restart.join();
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  EXPECT_EQ(client.reconnects(), 1u);
}

}  // namespace
}  // namespace flat2d::daemon
